// SPDX-License-Identifier: Apache-2.0
#include "tests/support/icc_files.h"

#include <lcms2.h>

namespace artcam::test {
namespace {

std::vector<unsigned char> saveProfile(cmsHPROFILE profile, const char* description) {
  cmsMLU* mlu = cmsMLUalloc(nullptr, 1);
  cmsMLUsetASCII(mlu, "en", "US", description);
  cmsWriteTag(profile, cmsSigProfileDescriptionTag, mlu);
  cmsMLUfree(mlu);
  cmsUInt32Number size = 0;
  cmsSaveProfileToMem(profile, nullptr, &size);
  std::vector<unsigned char> bytes(size);
  cmsSaveProfileToMem(profile, bytes.data(), &size);
  cmsCloseProfile(profile);
  return bytes;
}

}  // namespace

std::vector<unsigned char> adobeRgbProfile() {
  const cmsCIExyY white{kD65[0], kD65[1], 1.0};
  const cmsCIExyYTRIPLE primaries{{kAdobePrimaries[0][0], kAdobePrimaries[0][1], 1.0},
                                  {kAdobePrimaries[1][0], kAdobePrimaries[1][1], 1.0},
                                  {kAdobePrimaries[2][0], kAdobePrimaries[2][1], 1.0}};
  cmsToneCurve* curve = cmsBuildGamma(nullptr, kAdobeGamma);
  cmsToneCurve* curves[3] = {curve, curve, curve};
  cmsHPROFILE profile = cmsCreateRGBProfile(&white, &primaries, curves);
  cmsFreeToneCurve(curve);
  return saveProfile(profile, "Adobe RGB (1998)");
}

std::vector<unsigned char> greyGammaProfile(double gamma) {
  const cmsCIExyY white{kD65[0], kD65[1], 1.0};
  cmsToneCurve* curve = cmsBuildGamma(nullptr, gamma);
  cmsHPROFILE profile = cmsCreateGrayProfile(&white, curve);
  cmsFreeToneCurve(curve);
  return saveProfile(profile, "Grey gamma 2.2");
}

std::vector<unsigned char> labProfile() {
  return saveProfile(cmsCreateLab4Profile(nullptr), "Lab identity");
}

std::vector<unsigned char> cmykHeaderProfile() {
  std::vector<unsigned char> bytes(132, 0);
  const auto put = [&bytes](size_t at, const char* text) {
    for (size_t k = 0; text[k]; ++k) bytes[at + k] = static_cast<unsigned char>(text[k]);
  };
  bytes[3] = 132;  // size, big-endian
  put(4, "lcms");
  bytes[8] = 2;  // version 2.1
  bytes[9] = 0x10;
  put(12, "prtr");
  put(16, "CMYK");
  put(20, "Lab ");
  put(36, "acsp");
  return bytes;  // the tag count (bytes 128..131) stays 0
}

void setProfile(OIIO::ImageSpec& spec, const std::vector<unsigned char>& bytes) {
  spec.attribute("ICCProfile",
                 OIIO::TypeDesc(OIIO::TypeDesc::UINT8, static_cast<int>(bytes.size())),
                 bytes.data());
}

std::vector<unsigned char> profileOf(const OIIO::ImageSpec& spec) {
  const OIIO::ParamValue* p = spec.find_attribute("ICCProfile");
  if (!p) return {};
  const auto* first = static_cast<const unsigned char*>(p->data());
  return {first, first + p->type().size()};
}

bool write16(const std::string& path, int w, int h, int c, const std::vector<std::uint16_t>& data,
             const std::vector<unsigned char>& icc) {
  auto out = OIIO::ImageOutput::create(OIIO::string_view(path));
  if (!out) return false;
  OIIO::ImageSpec spec(w, h, c, OIIO::TypeDesc::UINT16);
  if (!icc.empty()) setProfile(spec, icc);
  return out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT16, data.data()) &&
         out->close();
}

}  // namespace artcam::test
