// SPDX-License-Identifier: Apache-2.0
#include "tests/support/porter_duff.h"

#include <stdexcept>

namespace artcam::test {

PremultipliedColour porterDuff(CompositeOp op, const PremultipliedColour& a,
                               const PremultipliedColour& b) {
  const double aa = a[3], ab = b[3];
  PremultipliedColour c;
  switch (op) {
    case CompositeOp::Over: return a + (1 - aa) * b;
    case CompositeOp::Under: return b + (1 - ab) * a;
    case CompositeOp::In: return a * ab;
    case CompositeOp::Out: return a * (1 - ab);
    case CompositeOp::Atop: return a * ab + b * (1 - aa);
    case CompositeOp::Xor: return a * (1 - ab) + b * (1 - aa);
    case CompositeOp::Add: return a + b;
    case CompositeOp::Multiply:
      for (int k = 0; k < 3; ++k) c[k] = a[k] * b[k] + a[k] * (1 - ab) + b[k] * (1 - aa);
      c[3] = aa + ab - aa * ab;
      return c;
    case CompositeOp::Screen:
      for (int k = 0; k < 3; ++k) c[k] = a[k] + b[k] - a[k] * b[k];
      c[3] = aa + ab - aa * ab;
      return c;
    case CompositeOp::Mix: return b;
  }
  throw std::logic_error("unknown operator");
}

}  // namespace artcam::test
