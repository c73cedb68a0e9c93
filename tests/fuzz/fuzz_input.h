// Reads a fuzzer's bytes as the values a fuzz target builds its input from; past the end every
// read gives 0, so any byte string is an input. make_seeds.cc writes the same encoding. (Read
// several values in one expression only inside braces, which fix the order.)
#ifndef FOGNAV_TESTS_FUZZ_FUZZ_INPUT_H_
#define FOGNAV_TESTS_FUZZ_FUZZ_INPUT_H_

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

namespace fognav::fuzz {

class FuzzInput {
 public:
  FuzzInput(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  size_t left() const { return size_ - at_; }

  uint8_t Byte() { return at_ < size_ ? data_[at_++] : 0; }

  // an integer in [lo, hi]
  int Int(int lo, int hi) {
    const uint32_t raw = uint32_t(Byte()) | uint32_t(Byte()) << 8;
    return lo + int(raw % uint32_t(hi - lo + 1));
  }

  // a number in [lo, hi] in 256 steps, or one of the values a sensor must survive: NaN, +-inf,
  // 0, the largest float
  float Value(float lo, float hi) {
    const uint8_t b = Byte();
    switch (b) {
      case 255:
        return std::numeric_limits<float>::quiet_NaN();
      case 254:
        return std::numeric_limits<float>::infinity();
      case 253:
        return -std::numeric_limits<float>::infinity();
      case 252:
        return 0.0f;
      case 251:
        return std::numeric_limits<float>::max();
      default:
        return lo + (hi - lo) * float(b) / 250.0f;
    }
  }

  // a number in [lo, hi] in 65536 steps (a pose: finite, as the callers guarantee)
  double Finite(double lo, double hi) {
    const uint32_t raw = uint32_t(Byte()) | uint32_t(Byte()) << 8;
    return lo + (hi - lo) * double(raw) / 65535.0;
  }

  // the raw bits of a float: any value, denormals and signalling NaNs included
  float RawFloat() {
    uint32_t bits = 0;
    for (int i = 0; i < 4; ++i) bits |= uint32_t(Byte()) << (8 * i);
    float value;
    std::memcpy(&value, &bits, sizeof(value));
    return value;
  }

 private:
  const uint8_t* data_;
  size_t size_;
  size_t at_ = 0;
};

}  // namespace fognav::fuzz

#endif  // FOGNAV_TESTS_FUZZ_FUZZ_INPUT_H_
