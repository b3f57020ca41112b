#include "p4/io/video_reader.h"

#include <cstring>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

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
  int stream = -1;
  VideoInfo info;
  bool draining = false;

  ~Impl() {
    sws_freeContext(sws);
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
  }
};

VideoReader::VideoReader(const std::string& source) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.source = source;
  int ret = avformat_open_input(&m.format, source.c_str(), nullptr, nullptr);
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

bool VideoReader::Read(I420Image* out, TimeNs* pts) {
  Impl& m = *impl_;
  while (true) {
    int ret = avcodec_receive_frame(m.codec, m.frame);
    if (ret == 0) {
      const AVRational tb = m.format->streams[m.stream]->time_base;
      const int64_t ts =
          m.frame->best_effort_timestamp == AV_NOPTS_VALUE ? 0 : m.frame->best_effort_timestamp;
      const int64_t start = m.format->streams[m.stream]->start_time;
      *pts = av_rescale_q(ts - (start == AV_NOPTS_VALUE ? 0 : start), tb,
                          AVRational{1, 1'000'000'000});
      const int w = m.frame->width, h = m.frame->height;
      if (out->width() != w || out->height() != h) *out = I420Image(w, h);
      uint8_t* dst[3] = {out->y(), out->u(), out->v()};
      const int dst_stride[3] = {w, w / 2, w / 2};
      if (m.frame->format == AV_PIX_FMT_YUV420P) {
        for (int p = 0; p < 3; ++p) {
          const int rows = p == 0 ? h : h / 2;
          for (int r = 0; r < rows; ++r) {
            std::memcpy(dst[p] + static_cast<std::ptrdiff_t>(r) * dst_stride[p],
                        m.frame->data[p] + static_cast<std::ptrdiff_t>(r) * m.frame->linesize[p],
                        dst_stride[p]);
          }
        }
      } else {
        m.sws = sws_getCachedContext(m.sws, w, h, static_cast<AVPixelFormat>(m.frame->format), w, h,
                                     AV_PIX_FMT_YUV420P, SWS_BILINEAR, nullptr, nullptr, nullptr);
        sws_scale(m.sws, m.frame->data, m.frame->linesize, 0, h, dst, dst_stride);
      }
      return true;
    }
    if (ret == AVERROR_EOF) return false;
    if (ret != AVERROR(EAGAIN)) throw Error(m.source + ": decoding failed: " + AvError(ret));
    if (m.draining) return false;
    ret = av_read_frame(m.format, m.packet);
    if (ret == AVERROR_EOF) {
      m.draining = true;
      avcodec_send_packet(m.codec, nullptr);
      continue;
    }
    if (ret < 0) throw Error(m.source + ": reading failed: " + AvError(ret));
    if (m.packet->stream_index == m.stream) {
      ret = avcodec_send_packet(m.codec, m.packet);
      av_packet_unref(m.packet);
      if (ret < 0 && ret != AVERROR(EAGAIN))
        throw Error(m.source + ": decoding failed: " + AvError(ret));
    } else {
      av_packet_unref(m.packet);
    }
  }
}

}  // namespace p4
