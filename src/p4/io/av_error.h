// FFmpeg error codes as text (internal to p4/io).
#pragma once

#include <string>

extern "C" {
#include <libavutil/error.h>
}

namespace p4 {

inline std::string AvError(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(code, text, sizeof(text));
  return text;
}

}  // namespace p4
