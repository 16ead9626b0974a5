!> Working precision and the physical and numerical constants shared by the kernel.
module voussoir_kinds
  use, intrinsic :: iso_fortran_env, only: real64, int32, int64
  implicit none
  private

  public :: dp, i8, pi, g_m_s2, tiny_length_m, tiny_real

  integer, parameter :: dp = real64  !! working real kind
  integer, parameter :: i8 = int64   !! long integer kind (counters)

  real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp
  real(dp), parameter :: g_m_s2 = 9.81_dp          !! gravity [m/s2]
  real(dp), parameter :: tiny_length_m = 1.0e-12_dp !! lengths below this are zero [m]
  real(dp), parameter :: tiny_real = 1.0e-300_dp    !! guard against division by zero
end module voussoir_kinds
