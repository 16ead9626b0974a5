!> The &load_cases group: several named load cases in one input, each with a partial
!> factor on its live loads (gamma_q) and one on every permanent load (gamma_g). A live
!> point load of &load belongs to the case `point_load_case(j)` names, or to every case
!> (0, the default; a vehicle's axles). Case k is then &load with its own live loads times
!> gamma_q(k) and the dead loads times gamma_g(k) (case_load); the limit analysis
!> multiplies the blocks' and the fill's weight by gamma_g(k) as well. Input only.
!> docs/bridges.md, "Load cases and partial factors".
module voussoir_load_case_config
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_load_config, only: load_config_t
  implicit none
  private
  public :: load_cases_t, load_cases_group, read_load_cases, check_load_cases, case_load, max_load_cases

  integer, parameter :: max_load_cases = 16
  real(dp), parameter :: unset_factor = -huge(1.0_dp)   !! a factor not given (its default: 1)

  !> &load_cases (absent: no cases, the loads of &load as given).
  type :: load_cases_t
    character(len=32) :: name(max_load_cases) = ''             !! case k's name; '' no case
    real(dp) :: gamma_q(max_load_cases) = unset_factor         !! partial factor on its live loads (1)
    real(dp) :: gamma_g(max_load_cases) = unset_factor         !! partial factor on every permanent load (1)
    integer :: n = 0                                           !! (derived) the cases given
  end type load_cases_t

contains

  !> The &load_cases table over `c`.
  subroutine load_cases_group(c, g)
    type(load_cases_t), intent(inout), target :: c
    type(nml_group_t), intent(out) :: g
    g%name = 'load_cases'
    call g%add('name', c%name, about='text, the name of load case k')
    call g%add('gamma_q', c%gamma_q, unset=unset_factor, range='0 < gamma_q <= 10', &
               about='real, the partial factor on the live loads of case k (default 1)')
    call g%add('gamma_g', c%gamma_g, unset=unset_factor, range='0 < gamma_g <= 10', &
               about='real, the partial factor on every permanent load of case k: the weights of the blocks '// &
               'and of the fill, its pressure, the dead loads of &load (default 1)')
  end subroutine load_cases_group

  !> Read the &load_cases group of `path` (absent: no cases); a factor left out is 1.
  subroutine read_load_cases(path, c, status)
    character(len=*), intent(in) :: path
    type(load_cases_t), intent(out), target :: c
    type(status_t), intent(inout) :: status
    type(nml_group_t) :: g
    integer :: k
    logical :: given
    if (.not. status%ok) return
    call load_cases_group(c, g)
    call g%read(path, status, given)
    if (.not. status%ok .or. .not. given) return
    c%n = g%length('name', path, status)
    if (.not. status%ok) return
    call g%check(path, status)
    if (.not. status%ok) return
    do k = c%n + 1, max_load_cases
      if (c%gamma_q(k) /= unset_factor .or. c%gamma_g(k) /= unset_factor) then
        call fail(status, path//': &load_cases gives a factor of case '//itoa(k)//' but no name(' //itoa(k)// &
                  '): name each case, from k = 1 without gaps')
        return
      end if
    end do
    if (c%n == 0) then
      call fail(status, path//': &load_cases gives no case: name(k) = ''...'' for each, with gamma_q(k) and '// &
                'gamma_g(k)')
      return
    end if
    where (c%gamma_q(1:c%n) == unset_factor) c%gamma_q(1:c%n) = 1.0_dp
    where (c%gamma_g(1:c%n) == unset_factor) c%gamma_g(1:c%n) = 1.0_dp
  end subroutine read_load_cases

  !> Refuse a case number of a point load outside the cases (or without &load_cases, or on
  !> a dead load) and a case without a live load of its own or of every case.
  subroutine check_load_cases(c, d, path, status)
    type(load_cases_t), intent(in) :: c
    type(load_config_t), intent(in) :: d
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    integer :: j, k
    if (.not. status%ok) return
    do j = 1, d%n_point_loads
      k = d%point_load_case(j)
      if (k == 0) cycle
      if (c%n == 0) then
        call fail(status, path//': &load point_load_case('//itoa(j)//') = '//itoa(k)//' names a load case, but '// &
                  'the file has no &load_cases (give the cases there, or leave point_load_case out)')
      else if (k > c%n) then
        call fail(status, path//': &load point_load_case('//itoa(j)//') = '//itoa(k)//': &load_cases has cases '// &
                  '1..'//itoa(c%n)//' (0: every case)')
      else if (.not. d%point_load_live(j)) then
        call fail(status, path//': &load point_load_case('//itoa(j)//') = '//itoa(k)//' on a dead load: the '// &
                  'dead loads stand in every case (times gamma_g); leave point_load_case out for it')
      end if
      if (.not. status%ok) return
    end do
    do k = 1, c%n
      if (any(d%point_load_live(1:d%n_point_loads) .and. &
              (d%point_load_case(1:d%n_point_loads) == 0 .or. d%point_load_case(1:d%n_point_loads) == k))) cycle
      call fail(status, path//': &load_cases case '//itoa(k)//" '"//trim(c%name(k))//"' has no live load: give "// &
                'it a live point load of &load with point_load_case(j) = '//itoa(k)//' (or 0: every case), or a '// &
                '&vehicle')
      return
    end do
  end subroutine check_load_cases

  !> &load as case k of `c` analyses it: the live point loads of case k or of every case
  !> times gamma_q(k), the dead point loads and the distributed dead load times gamma_g(k);
  !> the other cases' live loads left out.
  pure function case_load(d, c, k) result(e)
    type(load_config_t), intent(in) :: d
    type(load_cases_t), intent(in) :: c
    integer, intent(in) :: k
    type(load_config_t) :: e
    type(load_config_t) :: blank
    integer :: j, m
    e = d
    m = 0
    do j = 1, d%n_point_loads
      if (d%point_load_live(j) .and. d%point_load_case(j) /= 0 .and. d%point_load_case(j) /= k) cycle
      m = m + 1
      e%point_load_n(m) = d%point_load_n(j)*merge(c%gamma_q(k), c%gamma_g(k), d%point_load_live(j))
      e%point_load_dir_deg(m) = d%point_load_dir_deg(j)
      e%point_load_x_m(m) = d%point_load_x_m(j)
      e%point_load_y_m(m) = d%point_load_y_m(j)
      e%point_load_live(m) = d%point_load_live(j)
      e%point_load_patch_m(m) = d%point_load_patch_m(j)
      e%point_load_case(m) = 0
    end do
    e%point_load_n(m + 1:) = blank%point_load_n(m + 1:)
    e%point_load_dir_deg(m + 1:) = blank%point_load_dir_deg(m + 1:)
    e%point_load_x_m(m + 1:) = blank%point_load_x_m(m + 1:)
    e%point_load_y_m(m + 1:) = blank%point_load_y_m(m + 1:)
    e%point_load_live(m + 1:) = blank%point_load_live(m + 1:)
    e%point_load_patch_m(m + 1:) = blank%point_load_patch_m(m + 1:)
    e%point_load_case(m + 1:) = 0
    e%n_point_loads = m
    e%dead_load_n_per_m = d%dead_load_n_per_m*c%gamma_g(k)
  end function case_load

end module voussoir_load_case_config
