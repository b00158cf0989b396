// SPDX-License-Identifier: Apache-2.0
// Expected failures (a degenerate fit, an unreadable file) are values, not exceptions
// (docs/architecture.md, "Errors"): a Status carries one line a user can act on, naming the
// file, the place (line, JSON path) and the cause. Broken contracts still throw.
#pragma once

#include <optional>
#include <string>
#include <utility>

namespace artcam {

struct Status {
  bool ok = true;
  std::string message;  // empty when ok

  static Status success() { return {}; }
  static Status failure(std::string m) { return {false, std::move(m)}; }
  explicit operator bool() const { return ok; }
};

// A value or the Status that says why there is none.
template <class T>
struct Result {
  std::optional<T> value;
  Status status;

  static Result success(T v) { return {std::move(v), Status::success()}; }
  static Result failure(std::string m) { return {std::nullopt, Status::failure(std::move(m))}; }
  bool ok() const { return value.has_value(); }
  explicit operator bool() const { return ok(); }
  const T& operator*() const { return *value; }
  T& operator*() { return *value; }
  const T* operator->() const { return &*value; }
  T* operator->() { return &*value; }
};

}  // namespace artcam
