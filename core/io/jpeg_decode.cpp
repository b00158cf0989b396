// SPDX-License-Identifier: Apache-2.0
// libjpeg's errors arrive through error_exit, which must not return: it longjmps back to the
// setjmp of the call that entered libjpeg. Each such call (header, decode) is one function whose
// locals are plain values, so the jump skips no destructor; the decompressor itself is destroyed
// by ~State.
#include "core/io/jpeg_decode.h"

#include "core/io/io_text.h"

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include <jerror.h>
#include <jpeglib.h>

namespace artcam {

struct JpegDecoder::State {
  struct Errors {
    jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
    std::jmp_buf jump;
    char first_warning[JMSG_LENGTH_MAX] = {};
    char fatal[JMSG_LENGTH_MAX] = {};
    long warnings = 0;
  };
  std::string path;
  std::FILE* file = nullptr;
  jpeg_decompress_struct info{};
  Errors errors{};
  bool created = false;
  bool started = false;
  std::vector<unsigned char> icc;

  ~State() {
    if (created) jpeg_destroy_decompress(&info);
    if (file) std::fclose(file);
  }

  static void onFatal(j_common_ptr common) {
    Errors* e = reinterpret_cast<Errors*>(common->err);
    (*common->err->format_message)(common, e->fatal);
    std::longjmp(e->jump, 1);
  }
  // Warnings (level < 0) are damage (see the header); trace messages are dropped.
  static void onMessage(j_common_ptr common, int level) {
    if (level >= 0) return;
    Errors* e = reinterpret_cast<Errors*>(common->err);
    if (e->warnings++ == 0) (*common->err->format_message)(common, e->first_warning);
  }

  Status failure(const std::string& cause) const {
    return Status::failure(path + ": cannot read: " + io_text::oneLine(cause));
  }
  // The damage libjpeg reported, in decodeProblems' words; success when there is none.
  Status damage() const {
    if (errors.warnings == 0) return Status::success();
    std::string message = errors.first_warning;
    if (errors.warnings > 1) {
      const long more = errors.warnings - 1;
      message += " (and " + std::to_string(more) + " more decoder error" + (more == 1 ? "" : "s") +
                 ": the file is damaged or cut short)";
    }
    return failure(message);
  }
};

namespace {

// The header and output parameters; false when libjpeg failed (the message is in `state`).
bool readHeader(JpegDecoder::State& state, int scale_denominator, bool rgba) {
  if (setjmp(state.errors.jump)) return false;
  jpeg_create_decompress(&state.info);
  state.created = true;
  jpeg_stdio_src(&state.info, state.file);
  jpeg_save_markers(&state.info, JPEG_APP0 + 2, 0xFFFF);  // the ICC profile's
  jpeg_read_header(&state.info, TRUE);
  JOCTET* icc = nullptr;
  unsigned int icc_bytes = 0;
  if (jpeg_read_icc_profile(&state.info, &icc, &icc_bytes) && icc) {
    state.icc.assign(icc, icc + icc_bytes);
    std::free(icc);
  }
  const J_COLOR_SPACE in = state.info.jpeg_color_space;
  if (state.info.num_components == 1) state.info.out_color_space = JCS_GRAYSCALE;
  else if (in == JCS_YCbCr || in == JCS_RGB) state.info.out_color_space = rgba ? JCS_EXT_RGBA : JCS_RGB;
  state.info.scale_num = 1;
  state.info.scale_denom = static_cast<unsigned int>(scale_denominator);
  jpeg_calc_output_dimensions(&state.info);
  return true;
}

// Decodes into `pixels`; 1 done, 0 failed (message in `state`), -1 cancelled.
int decodeRows(JpegDecoder::State& state, std::uint8_t* pixels, std::size_t row_bytes,
               const std::function<bool(double)>* progress) {
  if (setjmp(state.errors.jump)) return 0;
  jpeg_start_decompress(&state.info);
  state.started = true;
  const JDIMENSION height = state.info.output_height;
  // Batches of rows: the progress hook and the damage check between them, libjpeg's own
  // rec_outbuf_height rows per call inside.
  constexpr JDIMENSION kBatch = 64;
  JSAMPROW rows[16];
  while (state.info.output_scanline < height) {
    const JDIMENSION batch_end = std::min(height, state.info.output_scanline + kBatch);
    while (state.info.output_scanline < batch_end) {
      const JDIMENSION first = state.info.output_scanline;
      const JDIMENSION n = std::min<JDIMENSION>(16, batch_end - first);
      for (JDIMENSION k = 0; k < n; ++k)
        rows[k] = pixels + static_cast<std::size_t>(first + k) * row_bytes;
      jpeg_read_scanlines(&state.info, rows, n);
    }
    // A truncated file turns the rest into grey with one warning: stop at the first.
    if (state.errors.warnings > 0) return 0;
    if (*progress && !(*progress)(static_cast<double>(state.info.output_scanline) / static_cast<double>(height)))
      return -1;
  }
  jpeg_finish_decompress(&state.info);
  return 1;
}

}  // namespace

JpegDecoder::JpegDecoder(std::unique_ptr<State> state) : state_(std::move(state)) {}
JpegDecoder::~JpegDecoder() = default;

Result<std::unique_ptr<JpegDecoder>> JpegDecoder::open(const std::string& path,
                                                       int scale_denominator, Output output) {
  using R = Result<std::unique_ptr<JpegDecoder>>;
  if (scale_denominator != 1 && scale_denominator != 2 && scale_denominator != 4 &&
      scale_denominator != 8)
    throw std::invalid_argument("JPEG scale denominator must be 1, 2, 4 or 8");
  auto state = std::make_unique<State>();
  state->path = path;
  state->file = std::fopen(path.c_str(), "rb");
  if (!state->file) return R::failure(path + ": cannot read: cannot open the file");
  state->info.err = jpeg_std_error(&state->errors.manager);
  state->errors.manager.error_exit = &State::onFatal;
  state->errors.manager.emit_message = &State::onMessage;
  if (!readHeader(*state, scale_denominator, output == Output::Rgba)) return R::failure(state->failure(state->errors.fatal).message);
  if (const Status damage = state->damage(); !damage) return R::failure(damage.message);
  return R::success(std::unique_ptr<JpegDecoder>(new JpegDecoder(std::move(state))));
}

int JpegDecoder::width() const { return static_cast<int>(state_->info.output_width); }
int JpegDecoder::height() const { return static_cast<int>(state_->info.output_height); }
int JpegDecoder::channels() const { return state_->info.out_color_components; }

const std::vector<unsigned char>& JpegDecoder::iccProfile() const { return state_->icc; }

bool JpegDecoder::supported() const {
  const jpeg_decompress_struct& info = state_->info;
  return info.data_precision == 8 &&
         ((info.num_components == 1 && info.out_color_space == JCS_GRAYSCALE) ||
          (info.num_components == 3 &&
           (info.out_color_space == JCS_RGB || info.out_color_space == JCS_EXT_RGBA)));
}

Status JpegDecoder::decode(std::uint8_t* pixels, std::size_t row_bytes,
                           const std::function<bool(double)>& progress) {
  if (state_->started) throw std::invalid_argument("JpegDecoder::decode called twice");
  if (!supported()) throw std::invalid_argument("JpegDecoder::decode on a file it does not take");
  if (row_bytes < static_cast<std::size_t>(width()) * static_cast<std::size_t>(channels()))
    throw std::invalid_argument("JpegDecoder::decode: rows shorter than the image");
  const int done = decodeRows(*state_, pixels, row_bytes, &progress);
  if (done < 0) return state_->failure("cancelled");
  if (done == 0 && state_->errors.warnings == 0) return state_->failure(state_->errors.fatal);
  return state_->damage();
}

}  // namespace artcam
