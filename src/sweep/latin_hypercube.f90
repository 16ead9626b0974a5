!> Latin hypercube samples: n points in the unit cube of d variables such that, in
!> every variable, each of the n equal strata [k/n, (k+1)/n) holds exactly one point
!> (McKay, Beckman and Conover 1979). Each variable gets its own random order of the
!> strata and a random position inside each; the stream is seeded, so a sweep draws the
!> same samples on every rank and every run.
module voussoir_latin_hypercube
  use voussoir_kinds, only: dp
  use voussoir_random_stream, only: random_stream_t, stream_init, stream_uniform
  implicit none
  private

  public :: latin_hypercube

contains

  !> `u(v, k)`: variable v of sample k, in (0, 1).
  function latin_hypercube(n_samples, n_vars, seed) result(u)
    integer, intent(in) :: n_samples, n_vars, seed
    real(dp) :: u(n_vars, n_samples)
    type(random_stream_t) :: s
    integer :: perm(n_samples), v, k, j, tmp
    real(dp) :: r
    s = stream_init(seed)
    do v = 1, n_vars
      ! Fisher-Yates shuffle of the strata.
      perm = [(k, k = 0, n_samples - 1)]
      do k = n_samples, 2, -1
        call stream_uniform(s, r)
        j = min(int(r*k) + 1, k)
        tmp = perm(k)
        perm(k) = perm(j)
        perm(j) = tmp
      end do
      do k = 1, n_samples
        call stream_uniform(s, r)
        u(v, k) = (perm(k) + r)/real(n_samples, dp)
      end do
    end do
  end function latin_hypercube

end module voussoir_latin_hypercube
