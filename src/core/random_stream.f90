!> A small, portable stream of pseudo-random numbers, so that seeded samples are the
!> same with every compiler and on every rank (Fortran's own `random_number` is not
!> specified and differs between compilers): L'Ecuyer's MRG32k3a, whose arithmetic is
!> exact in double precision.
module voussoir_random_stream
  use voussoir_kinds, only: dp
  implicit none
  private

  public :: random_stream_t, stream_init, stream_uniform

  real(dp), parameter :: m1 = 4294967087.0_dp, m2 = 4294944443.0_dp
  real(dp), parameter :: a12 = 1403580.0_dp, a13n = 810728.0_dp, a21 = 527612.0_dp, a23n = 1370589.0_dp
  real(dp), parameter :: norm = 2.328306549295727688e-10_dp
  integer, parameter :: warm_up = 16   !! numbers dropped after seeding

  !> The state of one stream.
  type :: random_stream_t
    real(dp) :: s1(3) = 12345.0_dp, s2(3) = 12345.0_dp
  end type random_stream_t

contains

  !> A stream started from `seed` (an integer >= 0; different seeds, different streams).
  function stream_init(seed) result(s)
    integer, intent(in) :: seed
    type(random_stream_t) :: s
    real(dp) :: u
    integer :: k
    s%s1(1) = 12345.0_dp + modulo(real(seed, dp), m1 - 12346.0_dp)
    s%s2(3) = 12345.0_dp + modulo(7.0_dp*real(seed, dp), m2 - 12346.0_dp)
    do k = 1, warm_up
      call stream_uniform(s, u)
    end do
  end function stream_init

  !> The next number, uniform in (0, 1).
  subroutine stream_uniform(s, u)
    type(random_stream_t), intent(inout) :: s
    real(dp), intent(out) :: u
    real(dp) :: p1, p2
    p1 = a12*s%s1(2) - a13n*s%s1(1)
    p1 = p1 - aint(p1/m1)*m1
    if (p1 < 0.0_dp) p1 = p1 + m1
    s%s1 = [s%s1(2), s%s1(3), p1]
    p2 = a21*s%s2(3) - a23n*s%s2(1)
    p2 = p2 - aint(p2/m2)*m2
    if (p2 < 0.0_dp) p2 = p2 + m2
    s%s2 = [s%s2(2), s%s2(3), p2]
    if (p1 <= p2) then
      u = (p1 - p2 + m1)*norm
    else
      u = (p1 - p2)*norm
    end if
  end subroutine stream_uniform

end module voussoir_random_stream
