#include "io/decimal.h"

namespace inertest::io_detail {

fast_float::from_chars_result parse_decimal_slowly(const char* first, const char* last, double& value) {
  return fast_float::from_chars(first, last, value);
}

}  // namespace inertest::io_detail
