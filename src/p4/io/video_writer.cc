#include "p4/io/video_writer.h"

#include <cmath>
#include <cstring>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
}

#include <fmt/format.h>

#include "p4/core/error.h"
#include "p4/io/av_error.h"

namespace p4 {

bool VideoWriterOptions::IsValid(std::string* error) const {
  if (width <= 0 || height <= 0 || width % 2 || height % 2) {
    if (error) *error = "video size must be positive and even";
    return false;
  }
  if (fps <= 0 || fps > 1000) {
    if (error) *error = "fps must be in [1, 1000]";
    return false;
  }
  return true;
}

const char* VideoExtension(VideoCodec codec) {
  return codec == VideoCodec::kH264 ? ".mp4" : ".mkv";
}

struct VideoWriter::Impl {
  std::string path;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  int64_t last_pts = 0;
  int64_t frames = 0;  // written so far
  bool closed = false;

  void Drain(bool flush) {
    if (flush) avcodec_send_frame(codec, nullptr);
    while (true) {
      const int ret = avcodec_receive_packet(codec, packet);
      if (ret == AVERROR(EAGAIN) || ret == AVERROR_EOF) return;
      if (ret < 0) throw Error(path + ": encoding failed: " + AvError(ret));
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      const int w = av_interleaved_write_frame(format, packet);
      if (w < 0) throw Error(path + ": writing failed: " + AvError(w));
    }
  }

  ~Impl() {
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    if (format) {
      if (!(format->oformat->flags & AVFMT_NOFILE)) avio_closep(&format->pb);
      avformat_free_context(format);
    }
  }
};

VideoWriter::VideoWriter(const std::string& path, const VideoWriterOptions& options)
    : impl_(std::make_unique<Impl>()) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(path + ": " + why);
  Impl& m = *impl_;
  m.path = path;
  av_log_set_level(AV_LOG_ERROR);  // encoder statistics are noise on a user's terminal
  int ret = avformat_alloc_output_context2(&m.format, nullptr, nullptr, path.c_str());
  if (ret < 0 || !m.format) throw Error(path + ": cannot choose a container: " + AvError(ret));
  const AVCodec* encoder = options.codec == VideoCodec::kH264
                               ? avcodec_find_encoder_by_name("libx264")
                               : avcodec_find_encoder(AV_CODEC_ID_FFV1);
  if (!encoder) throw Error(path + ": the FFmpeg build has no encoder for this codec");
  m.stream = avformat_new_stream(m.format, nullptr);
  m.codec = avcodec_alloc_context3(encoder);
  m.codec->width = options.width;
  m.codec->height = options.height;
  m.codec->pix_fmt = AV_PIX_FMT_YUV420P;
  m.codec->time_base = AVRational{1, options.time_base_hz > 0 ? options.time_base_hz : options.fps};
  m.codec->framerate = AVRational{options.fps, 1};
  m.codec->color_range = AVCOL_RANGE_MPEG;
  m.codec->colorspace = AVCOL_SPC_SMPTE170M;
  m.codec->color_primaries = AVCOL_PRI_SMPTE170M;
  m.codec->color_trc = AVCOL_TRC_SMPTE170M;
  m.codec->thread_count = options.threads;
  m.codec->gop_size = options.fps;
  if (m.format->oformat->flags & AVFMT_GLOBALHEADER) m.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (options.codec == VideoCodec::kH264) {
    av_opt_set(m.codec->priv_data, "preset", options.preset.c_str(), 0);
    av_opt_set(m.codec->priv_data, "crf", std::to_string(options.crf).c_str(), 0);
  } else {
    m.codec->level = 3;
  }
  ret = avcodec_open2(m.codec, encoder, nullptr);
  if (ret < 0) throw Error(path + ": cannot open the encoder: " + AvError(ret));
  avcodec_parameters_from_context(m.stream->codecpar, m.codec);
  m.stream->time_base = m.codec->time_base;
  m.stream->avg_frame_rate = m.codec->framerate;
  m.stream->r_frame_rate = m.codec->framerate;
  if (!(m.format->oformat->flags & AVFMT_NOFILE)) {
    ret = avio_open(&m.format->pb, path.c_str(), AVIO_FLAG_WRITE);
    if (ret < 0) throw Error(path + ": cannot create the file: " + AvError(ret));
  }
  ret = avformat_write_header(m.format, nullptr);
  if (ret < 0) throw Error(path + ": cannot write the header: " + AvError(ret));
  m.frame = av_frame_alloc();
  m.frame->format = AV_PIX_FMT_YUV420P;
  m.frame->width = options.width;
  m.frame->height = options.height;
  if (av_frame_get_buffer(m.frame, 0) < 0) throw Error(path + ": out of memory");
  m.packet = av_packet_alloc();
}

VideoWriter::~VideoWriter() {
  try {
    Close();
  } catch (...) {
    // Destructors do not throw; Close() explicitly to see errors.
  }
}

void VideoWriter::Write(const I420Image& image) {
  const Impl& m = *impl_;
  Write(image, FromSeconds(static_cast<double>(m.frames) / m.codec->framerate.num));
}

void VideoWriter::Write(const I420Image& image, TimeNs stamp) {
  Impl& m = *impl_;
  const int64_t pts = std::llround(ToSeconds(stamp) * m.codec->time_base.den);
  if (m.frames > 0 && pts <= m.last_pts) {
    throw Error(fmt::format("{}: frame stamped {:.6f} s is not after the last one", m.path,
                            ToSeconds(stamp)));
  }
  if (image.width() != m.codec->width || image.height() != m.codec->height) {
    throw Error(m.path + ": frame size differs from the video size");
  }
  if (av_frame_make_writable(m.frame) < 0) throw Error(m.path + ": out of memory");
  const uint8_t* planes[3] = {image.y(), image.u(), image.v()};
  const int widths[3] = {image.width(), image.chroma_width(), image.chroma_width()};
  const int heights[3] = {image.height(), image.chroma_height(), image.chroma_height()};
  for (int p = 0; p < 3; ++p) {
    for (int row = 0; row < heights[p]; ++row) {
      std::memcpy(m.frame->data[p] + static_cast<std::ptrdiff_t>(row) * m.frame->linesize[p],
                  planes[p] + static_cast<std::ptrdiff_t>(row) * widths[p], widths[p]);
    }
  }
  m.frame->pts = pts;
  m.last_pts = pts;
  ++m.frames;
  const int ret = avcodec_send_frame(m.codec, m.frame);
  if (ret < 0) throw Error(m.path + ": encoding failed: " + AvError(ret));
  m.Drain(false);
}

void VideoWriter::Close() {
  Impl& m = *impl_;
  if (m.closed) return;
  m.closed = true;
  m.Drain(true);
  const int ret = av_write_trailer(m.format);
  if (ret < 0) throw Error(m.path + ": cannot finish the file: " + AvError(ret));
}

}  // namespace p4
