#pragma once
/// Test support: floating-point traps (issue 9, determinism). While a FloatingPointTraps
/// lives, an invalid operation (NaN from non-NaN), a division by zero or an overflow in
/// this thread raises SIGFPE, so a frame that makes a NaN or an infinity fails its test at
/// the operation instead of being zeroed and counted later. Only around engine code:
/// Embree's traversal divides by zero on purpose.

#include <cfenv>

namespace voxhap::test {

class FloatingPointTraps {
public:
  FloatingPointTraps() : previous_(fegetexcept()) {
    std::feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
  }
  ~FloatingPointTraps() {
    fedisableexcept(FE_ALL_EXCEPT);
    std::feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(previous_);
  }
  FloatingPointTraps(const FloatingPointTraps&) = delete;
  FloatingPointTraps& operator=(const FloatingPointTraps&) = delete;

private:
  int previous_;
};

}  // namespace voxhap::test
