#include "p4/io/video_reader.h"

#include <cstring>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavdevice/avdevice.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/log.h>
#include <libswscale/swscale.h>
}

#include <cmath>
#include <mutex>
#include <utility>

#include "p4/core/error.h"
#include "p4/io/av_error.h"

namespace p4 {

struct VideoReader::Impl {
  std::string source;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  I420Image converted;
  int stream = -1;
  VideoInfo info;
  bool draining = false;
  std::string ended_with;
  // Damage: skipped since the last good frame, the gaps closed so far.
  std::optional<TimeNs> last_good;
  int64_t pending = 0;
  int consecutive_errors = 0;
  std::vector<VideoGap> gaps;

  TimeNs FramePts() const {
    const AVStream* st = format->streams[stream];
    const int64_t ts =
        frame->best_effort_timestamp == AV_NOPTS_VALUE ? 0 : frame->best_effort_timestamp;
    const int64_t start = st->start_time;
    return av_rescale_q(ts - (start == AV_NOPTS_VALUE ? 0 : start), st->time_base,
                        AVRational{1, 1'000'000'000});
  }
  // Closes the open gap, if any, at a good frame's time (none: at the end).
  void CloseGap(std::optional<TimeNs> t) {
    if (pending > 0) {
      VideoGap g;
      g.after = last_good;
      g.before = t;
      g.damaged = pending;
      g.frames_lost = pending;
      if (t && info.fps > 0.0) {
        const double span = ToSeconds(*t - last_good.value_or(0)) * info.fps;
        const auto by_rate = static_cast<int64_t>(std::llround(span)) - (last_good ? 1 : 0);
        g.frames_lost = std::max<int64_t>(by_rate, 0);
      }
      gaps.push_back(g);
    }
    pending = 0;
    if (t) last_good = t;
  }

  ~Impl() {
    sws_freeContext(sws);
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
  }
};

void ShowFfmpegMessages(bool verbose) { av_log_set_level(verbose ? AV_LOG_INFO : AV_LOG_FATAL); }

bool VideoReader::IsLive(const std::string& source) {
  return source.rfind("/dev/video", 0) == 0 || source.find("://") != std::string::npos;
}

VideoReader::VideoReader(const std::string& source) : impl_(std::make_unique<Impl>()) {
  static std::once_flag once;
  std::call_once(once, [] {
    avdevice_register_all();
    avformat_network_init();
  });
  Impl& m = *impl_;
  m.source = source;
  const AVInputFormat* input_format = nullptr;
  AVDictionary* options = nullptr;
  if (source.rfind("/dev/video", 0) == 0) {
    input_format = av_find_input_format("video4linux2");
    if (!input_format) throw Error(source + ": this FFmpeg has no V4L2 input");
  } else if (source.rfind("rtsp://", 0) == 0) {
    av_dict_set(&options, "rtsp_transport", "tcp", 0);
    av_dict_set(&options, "timeout", "5000000", 0);  // us
  } else if (source.find("://") != std::string::npos) {
    av_dict_set(&options, "timeout", "5000000", 0);
  }
  int ret = avformat_open_input(&m.format, source.c_str(), input_format, &options);
  av_dict_free(&options);
  if (ret < 0 && source.rfind("rtsp://", 0) == 0) {
    // RTP over the RTSP connection (TCP) is refused by some servers: try RTP over UDP.
    const std::string tcp_error = AvError(ret);
    av_dict_set(&options, "rtsp_transport", "udp", 0);
    av_dict_set(&options, "timeout", "5000000", 0);
    ret = avformat_open_input(&m.format, source.c_str(), nullptr, &options);
    av_dict_free(&options);
    if (ret < 0) {
      throw Error(source + ": cannot open: " + tcp_error + " (TCP), " + AvError(ret) + " (UDP)");
    }
  }
  if (ret < 0) throw Error(source + ": cannot open: " + AvError(ret));
  ret = avformat_find_stream_info(m.format, nullptr);
  if (ret < 0) throw Error(source + ": cannot read stream info: " + AvError(ret));
  const AVCodec* decoder = nullptr;
  m.stream = av_find_best_stream(m.format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (m.stream < 0 || !decoder) throw Error(source + ": no video stream");
  AVStream* st = m.format->streams[m.stream];
  m.codec = avcodec_alloc_context3(decoder);
  avcodec_parameters_to_context(m.codec, st->codecpar);
  m.codec->thread_count = 1;
  ret = avcodec_open2(m.codec, decoder, nullptr);
  if (ret < 0) throw Error(source + ": cannot open the decoder: " + AvError(ret));
  m.info.width = m.codec->width;
  m.info.height = m.codec->height;
  const AVRational rate = st->avg_frame_rate.num ? st->avg_frame_rate : st->r_frame_rate;
  m.info.fps = rate.den ? av_q2d(rate) : 0.0;
  m.info.frame_count = st->nb_frames;
  m.frame = av_frame_alloc();
  m.packet = av_packet_alloc();
}

VideoReader::~VideoReader() = default;

const VideoInfo& VideoReader::info() const { return impl_->info; }

bool VideoReader::ReadView(ImageView* view, TimeNs* pts) {
  Impl& m = *impl_;
  // A decoder or container that fails this often in a row with nothing good between is not
  // damaged in a stretch: the stream ends there.
  constexpr int kMaxConsecutiveErrors = 10'000;
  const auto end = [&](const std::string& why) {
    if (m.ended_with.empty() && !why.empty()) m.ended_with = m.source + ": " + why;
    m.CloseGap(std::nullopt);
    return false;
  };
  while (true) {
    int ret = avcodec_receive_frame(m.codec, m.frame);
    if (ret == 0) {
      // Concealed or missing a reference: the picture is partly made up. Skipped (the frames
      // around it are good; a made-up patch could look like a ball).
      if ((m.frame->flags & AV_FRAME_FLAG_CORRUPT) != 0 || m.frame->decode_error_flags != 0) {
        ++m.pending;
        continue;
      }
      m.consecutive_errors = 0;
      *pts = m.FramePts();
      m.CloseGap(*pts);
      const int w = m.frame->width, h = m.frame->height;
      view->width = w;
      view->height = h;
      const auto plane = [&](int p, int pw, int ph) {
        return PlaneView{m.frame->data[p], pw, ph, m.frame->linesize[p]};
      };
      switch (m.frame->format) {
        case AV_PIX_FMT_YUV420P:
        case AV_PIX_FMT_YUVJ420P:
          view->format = PixelFormat::kI420;
          view->planes[0] = plane(0, w, h);
          view->planes[1] = plane(1, w / 2, h / 2);
          view->planes[2] = plane(2, w / 2, h / 2);
          return true;
        case AV_PIX_FMT_NV12:
          view->format = PixelFormat::kNV12;
          view->planes[0] = plane(0, w, h);
          view->planes[1] = plane(1, w / 2, h / 2);
          view->planes[2] = {};
          return true;
        case AV_PIX_FMT_YUYV422:
          view->format = PixelFormat::kYUYV;
          view->planes[0] = plane(0, w, h);
          view->planes[1] = view->planes[2] = {};
          return true;
        default: {
          if (m.converted.width() != w || m.converted.height() != h) m.converted = I420Image(w, h);
          uint8_t* dst[3] = {m.converted.y(), m.converted.u(), m.converted.v()};
          const int dst_stride[3] = {w, w / 2, w / 2};
          m.sws =
              sws_getCachedContext(m.sws, w, h, static_cast<AVPixelFormat>(m.frame->format), w, h,
                                   AV_PIX_FMT_YUV420P, SWS_BILINEAR, nullptr, nullptr, nullptr);
          sws_scale(m.sws, m.frame->data, m.frame->linesize, 0, h, dst, dst_stride);
          *view = m.converted.View();
          return true;
        }
      }
    }
    if (ret == AVERROR_EOF) return end("");
    if (ret != AVERROR(EAGAIN)) {
      // The decoder gave up on a picture: skipped.
      ++m.pending;
      if (++m.consecutive_errors >= kMaxConsecutiveErrors)
        return end("decoding failed: " + AvError(ret));
      continue;
    }
    if (m.draining) return end("");
    ret = av_read_frame(m.format, m.packet);
    if (ret < 0) {
      // Bad bytes in a file: the demuxer may resync on the next packet; anything else (a cut
      // file, a lost connection) ends the stream as its end would, the decoder drained.
      const bool damaged =
          ret == AVERROR_INVALIDDATA && ++m.consecutive_errors < kMaxConsecutiveErrors;
      if (damaged) {
        ++m.pending;
        continue;
      }
      if (ret != AVERROR_EOF) m.ended_with = m.source + ": reading stopped: " + AvError(ret);
      m.draining = true;
      avcodec_send_packet(m.codec, nullptr);
      continue;
    }
    if (m.packet->stream_index == m.stream) {
      ret = avcodec_send_packet(m.codec, m.packet);
      av_packet_unref(m.packet);
      if (ret < 0 && ret != AVERROR(EAGAIN)) {
        ++m.pending;  // a packet the decoder refuses: its frame is lost
        if (++m.consecutive_errors >= kMaxConsecutiveErrors)
          return end("decoding failed: " + AvError(ret));
      }
    } else {
      av_packet_unref(m.packet);
    }
  }
}

bool VideoReader::Read(I420Image* out, TimeNs* pts) {
  ImageView view;
  if (!ReadView(&view, pts)) return false;
  if (out->width() != view.width || out->height() != view.height)
    *out = I420Image(view.width, view.height);
  const int w = view.width, h = view.height;
  for (int r = 0; r < h; ++r) {
    for (int x = 0; x < w; ++x) {
      switch (view.format) {
        case PixelFormat::kI420:
        case PixelFormat::kNV12:
          out->y()[r * w + x] = view.planes[0].Row(r)[x];
          break;
        case PixelFormat::kYUYV:
          out->y()[r * w + x] = view.planes[0].Row(r)[2 * x];
          break;
      }
    }
  }
  for (int r = 0; r < h / 2; ++r) {
    for (int x = 0; x < w / 2; ++x) {
      uint8_t u = 0, v = 0;
      switch (view.format) {
        case PixelFormat::kI420:
          u = view.planes[1].Row(r)[x], v = view.planes[2].Row(r)[x];
          break;
        case PixelFormat::kNV12:
          u = view.planes[1].Row(r)[2 * x], v = view.planes[1].Row(r)[2 * x + 1];
          break;
        case PixelFormat::kYUYV:  // 4:2:2: take the even row's chroma
          u = view.planes[0].Row(2 * r)[4 * x + 1], v = view.planes[0].Row(2 * r)[4 * x + 3];
          break;
      }
      out->u()[r * (w / 2) + x] = u;
      out->v()[r * (w / 2) + x] = v;
    }
  }
  return true;
}

std::vector<VideoGap> VideoReader::TakeGaps() { return std::exchange(impl_->gaps, {}); }

const std::string& VideoReader::ended_with() const { return impl_->ended_with; }

}  // namespace p4
