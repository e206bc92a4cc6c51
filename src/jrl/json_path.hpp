#pragma once
// A JSON path for error messages ("measurements.b[12].measurements[1].covariance"), built as a chain of stack
// frames so that the happy path allocates nothing; str() is called only when reporting an error.
#include <cstddef>
#include <string>
#include <string_view>

namespace cosmo::jrl::detail {

class JsonPath {
 public:
  JsonPath() = default;
  JsonPath field(std::string_view name) const { return JsonPath(this, name, 0, false); }
  JsonPath index(std::size_t i) const { return JsonPath(this, {}, i, true); }

  std::string str() const {
    std::string s = parent_ ? parent_->str() : std::string();
    if (is_index_) return s + "[" + std::to_string(index_) + "]";
    if (name_.empty()) return s;
    return s.empty() ? std::string(name_) : s + "." + std::string(name_);
  }

 private:
  JsonPath(const JsonPath* parent, std::string_view name, std::size_t index, bool is_index)
      : parent_(parent), name_(name), index_(index), is_index_(is_index) {}
  const JsonPath* parent_ = nullptr;
  std::string_view name_;
  std::size_t index_ = 0;
  bool is_index_ = false;
};

}  // namespace cosmo::jrl::detail
