// SPDX-License-Identifier: Apache-2.0
#include "core/colour/icc_profile.h"

#include "core/colour/transfer.h"

#include <lcms2.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace artcam {

namespace {

using ProfileHandle = std::unique_ptr<void, decltype(&cmsCloseProfile)>;

const cmsCIExyY kD65{0.3127, 0.3290, 1.0};

// The working space as an lcms2 profile (see the header): Rec.709 primaries, D65, linear.
ProfileHandle workingProfile(int colour_channels) {
  cmsToneCurve* linear = cmsBuildGamma(nullptr, 1.0);
  cmsHPROFILE profile = nullptr;
  if (colour_channels == 1) {
    profile = cmsCreateGrayProfile(&kD65, linear);
  } else {
    const cmsCIExyYTRIPLE rec709{{0.64, 0.33, 1.0}, {0.30, 0.60, 1.0}, {0.15, 0.06, 1.0}};
    cmsToneCurve* curves[3] = {linear, linear, linear};
    profile = cmsCreateRGBProfile(&kD65, &rec709, curves);
  }
  cmsFreeToneCurve(linear);
  return ProfileHandle(profile, &cmsCloseProfile);
}

std::string profileDescription(cmsHPROFILE profile) {
  char text[256] = {};
  const cmsUInt32Number n =
      cmsGetProfileInfoASCII(profile, cmsInfoDescription, "en", "US", text, sizeof(text));
  std::string description = n > 0 ? std::string(text) : std::string();
  // One line: a description with control characters would break the messages that name it.
  for (char& c : description)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) == 0x7f) c = ' ';
  while (!description.empty() && description.back() == ' ') description.pop_back();
  return description.empty() ? "unnamed profile" : description;
}

std::string colourSpaceName(cmsColorSpaceSignature space) {
  switch (space) {
    case cmsSigRgbData:
      return "RGB";
    case cmsSigGrayData:
      return "grey";
    case cmsSigCmykData:
      return "CMYK";
    case cmsSigLabData:
      return "Lab";
    case cmsSigXYZData:
      return "XYZ";
    case cmsSigYCbCrData:
      return "YCbCr";
    default:
      return "a non-RGB colour space";
  }
}

// Runs `transform` over the colour channels of interleaved pixels, a band at a time.
void applyTransform(cmsHTRANSFORM transform, int colour_channels, float* data, size_t pixels,
                    int channels, int alpha_channel) {
  if (channels - (alpha_channel >= 0 ? 1 : 0) != colour_channels)
    throw std::invalid_argument("IccProfile: pixels with other colour channels than the profile");
  constexpr size_t kBand = 4096;
  std::vector<float> band(kBand * static_cast<size_t>(colour_channels));
  const size_t stride = static_cast<size_t>(channels);
  for (size_t first = 0; first < pixels; first += kBand) {
    const size_t count = std::min(kBand, pixels - first);
    float* px = data + first * stride;
    size_t k = 0;
    for (size_t p = 0; p < count; ++p)
      for (int c = 0; c < channels; ++c)
        if (c != alpha_channel) band[k++] = px[p * stride + static_cast<size_t>(c)];
    cmsDoTransform(transform, band.data(), band.data(), static_cast<cmsUInt32Number>(count));
    k = 0;
    for (size_t p = 0; p < count; ++p)
      for (int c = 0; c < channels; ++c)
        if (c != alpha_channel) px[p * stride + static_cast<size_t>(c)] = band[k++];
  }
}

}  // namespace

struct IccProfile::Transforms {
  cmsHTRANSFORM to_working = nullptr;
  cmsHTRANSFORM from_working = nullptr;
  ~Transforms() {
    if (to_working) cmsDeleteTransform(to_working);
    if (from_working) cmsDeleteTransform(from_working);
  }
};

bool IccProfile::describesCmyk(const std::vector<unsigned char>& bytes) {
  if (bytes.empty()) return false;
  ProfileHandle file(
      cmsOpenProfileFromMem(bytes.data(), static_cast<cmsUInt32Number>(bytes.size())),
      &cmsCloseProfile);
  return file && cmsGetColorSpace(file.get()) == cmsSigCmykData;
}

Result<IccProfile> IccProfile::fromBytes(const std::vector<unsigned char>& bytes,
                                         int colour_channels, const std::string& path) {
  using R = Result<IccProfile>;
  if (colour_channels != 1 && colour_channels != 3)
    throw std::invalid_argument("IccProfile: colour_channels must be 1 or 3");
  const std::string fail = path + ": cannot read: its embedded ICC profile ";
  if (bytes.empty()) return R::failure(fail + "is empty");
  ProfileHandle file(
      cmsOpenProfileFromMem(bytes.data(), static_cast<cmsUInt32Number>(bytes.size())),
      &cmsCloseProfile);
  if (!file) return R::failure(fail + "is damaged (lcms2 cannot parse it)");
  const cmsColorSpaceSignature space = cmsGetColorSpace(file.get());
  const cmsColorSpaceSignature wanted = colour_channels == 1 ? cmsSigGrayData : cmsSigRgbData;
  if (space != wanted)
    return R::failure(fail + "describes " + colourSpaceName(space) + " colour, the pixels are " +
                      (colour_channels == 1 ? "grey" : "RGB"));

  IccProfile profile;
  profile.bytes_ = bytes;
  profile.description_ = profileDescription(file.get());
  profile.colour_channels_ = colour_channels;
  const ProfileHandle working = workingProfile(colour_channels);
  const cmsUInt32Number format = colour_channels == 1 ? TYPE_GRAY_FLT : TYPE_RGB_FLT;
  constexpr cmsUInt32Number kFlags = cmsFLAGS_NOOPTIMIZE | cmsFLAGS_NOCACHE;
  auto transforms = std::make_shared<Transforms>();
  transforms->to_working = cmsCreateTransform(file.get(), format, working.get(), format,
                                              INTENT_RELATIVE_COLORIMETRIC, kFlags);
  transforms->from_working = cmsCreateTransform(working.get(), format, file.get(), format,
                                                INTENT_RELATIVE_COLORIMETRIC, kFlags);
  if (!transforms->to_working || !transforms->from_working)
    return R::failure(fail +
                      (profile.description_ == "unnamed profile"
                           ? std::string()
                           : "(\"" + profile.description_ + "\") ") +
                      "is unusable (lcms2 cannot convert through it)");
  profile.transforms_ = std::move(transforms);
  return R::success(std::move(profile));
}

std::vector<unsigned char> IccProfile::srgbBytes() {
  ProfileHandle srgb(cmsCreate_sRGBProfile(), &cmsCloseProfile);
  cmsUInt32Number size = 0;
  if (!srgb || !cmsSaveProfileToMem(srgb.get(), nullptr, &size) || size == 0)
    throw std::runtime_error("lcms2 cannot make its sRGB profile");
  std::vector<unsigned char> bytes(size);
  if (!cmsSaveProfileToMem(srgb.get(), bytes.data(), &size))
    throw std::runtime_error("lcms2 cannot serialise its sRGB profile");
  bytes.resize(size);
  return bytes;
}

bool IccProfile::equivalentToSrgb() const {
  constexpr double kTolerance = 1e-3;
  constexpr int kSteps = 8;
  const Transfer srgb = Transfer::srgb();
  std::vector<float> grid;
  if (colour_channels_ == 1) {
    for (int i = 0; i <= kSteps; ++i) grid.push_back(static_cast<float>(i) / kSteps);
  } else {
    for (int r = 0; r <= kSteps; ++r)
      for (int g = 0; g <= kSteps; ++g)
        for (int b = 0; b <= kSteps; ++b)
          for (int v : {r, g, b}) grid.push_back(static_cast<float>(v) / kSteps);
  }
  std::vector<float> linear = grid;
  toWorking(linear.data(), grid.size() / static_cast<size_t>(colour_channels_), colour_channels_,
            -1);
  for (size_t k = 0; k < grid.size(); ++k)
    if (!(std::abs(linear[k] - srgb.decode(grid[k])) <= kTolerance)) return false;
  return true;
}

void IccProfile::toWorking(float* data, size_t pixels, int channels, int alpha_channel) const {
  applyTransform(transforms_->to_working, colour_channels_, data, pixels, channels, alpha_channel);
}

void IccProfile::fromWorking(float* data, size_t pixels, int channels, int alpha_channel) const {
  applyTransform(transforms_->from_working, colour_channels_, data, pixels, channels,
                 alpha_channel);
}

}  // namespace artcam
