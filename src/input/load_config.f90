!> The &load group: point loads (dead or live) at points of the blocks, an axle group
!> (each live point load repeated at offsets along x), a distributed dead load on the top
!> of the blocks over a range of x, and the path along which the live loads move to find
!> their critical position. A live point load may be a patch: spread uniformly over a
!> length along x (a tyre's contact), on the top surface or the fill's. Input only: the loads are placed on the blocks by
!> voussoir_placed_loads (src/assembly/placed_loads.f90). docs/limit_analysis.md, "Loads".
module voussoir_load_config
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_real
  use voussoir_namelist_group, only: nml_group_t, config_entry_t
  use voussoir_input_range, only: need
  implicit none
  private
  public :: load_config_t, load_group, read_load_config, load_entries, max_point_loads, max_axles

  integer, parameter :: max_point_loads = 16   !! point loads of one &load group
  integer, parameter :: max_axles = 8          !! offsets of an axle group
  real(dp), parameter :: default_dir_deg = -90.0_dp

  !> &load (no point load, no dead load and no path: no &load, the live load is the
  !> horizontal acceleration lambda g towards +x).
  type :: load_config_t
    real(dp) :: point_load_n(max_point_loads) = 0.0_dp                 !! magnitude [N]; 0: no load
    real(dp) :: point_load_dir_deg(max_point_loads) = default_dir_deg  !! direction from +x [deg], -90 downwards
    real(dp) :: point_load_x_m(max_point_loads) = 0.0_dp               !! point of application [m]
    real(dp) :: point_load_y_m(max_point_loads) = 0.0_dp
    logical :: point_load_live(max_point_loads) = .true.               !! live (times the load factor) or dead
    !> A live load spread uniformly over this length along x, centred on its x [m]; 0: a point
    real(dp) :: point_load_patch_m(max_point_loads) = 0.0_dp
    !> The load case (&load_cases) of a live load; 0: every case
    integer :: point_load_case(max_point_loads) = 0
    real(dp) :: axle_spacing_m(max_axles) = 0.0_dp      !! each live load repeated at these x offsets [m]
    real(dp) :: dead_load_n_per_m = 0.0_dp              !! a vertical dead load per metre of x [N/m]
    real(dp) :: dead_load_x0_m = 0.0_dp                 !! from x0 to x1 [m], on the top of the blocks
    real(dp) :: dead_load_x1_m = 0.0_dp
    real(dp) :: path_x0_m = 0.0_dp                      !! the live loads moved along x from x0 to x1 [m]
    real(dp) :: path_x1_m = 0.0_dp
    integer :: path_points = 0                          !! positions on the path; 0: no path
    integer :: n_point_loads = 0                        !! (derived) the point loads given
    integer :: n_axles = 0                              !! (derived) the axle offsets given
  end type load_config_t

contains

  !> The &load table over `d`.
  subroutine load_group(d, g)
    type(load_config_t), intent(inout), target :: d
    type(nml_group_t), intent(out) :: g
    g%name = 'load'
    call g%add('point_load_n', d%point_load_n, unset=0.0_dp, unit='N', range='0 < point_load_n <= 1e12 N', &
               about='real, N, the magnitude of point load j')
    call g%add('point_load_dir_deg', d%point_load_dir_deg, unit='deg', &
               range='-360 <= point_load_dir_deg <= 360 deg', about='real, deg from +x, -90 downwards')
    call g%add('point_load_x_m', d%point_load_x_m, unit='m', range='-1000 <= point_load_x_m <= 1000 m')
    call g%add('point_load_y_m', d%point_load_y_m, unit='m', range='-1000 <= point_load_y_m <= 1000 m')
    call g%add('point_load_live', d%point_load_live, about='logical, .true. live, .false. dead')
    call g%add('point_load_patch_m', d%point_load_patch_m, unit='m', range='0 <= point_load_patch_m <= 100 m', &
               about='real, m, the length along x a live load is spread over (0: a point)')
    call g%add('point_load_case', d%point_load_case, range='0 <= point_load_case <= 16', &
               about='integer, the load case of &load_cases a live load belongs to (0: every case)')
    call g%add('axle_spacing_m', d%axle_spacing_m, unset=0.0_dp, unit='m', &
               range='-1000 <= axle_spacing_m <= 1000 m', about='real, m, the x offset of axle j from the first')
    call g%add('dead_load_n_per_m', d%dead_load_n_per_m, unit='N/m', range='0 <= dead_load_n_per_m <= 1e12 N/m')
    call g%add('dead_load_x0_m', d%dead_load_x0_m, unit='m', range='-1000 <= dead_load_x0_m <= 1000 m')
    call g%add('dead_load_x1_m', d%dead_load_x1_m, unit='m', range='-1000 <= dead_load_x1_m <= 1000 m')
    call g%add('path_x0_m', d%path_x0_m, unit='m', range='-1000 <= path_x0_m <= 1000 m')
    call g%add('path_x1_m', d%path_x1_m, unit='m', range='-1000 <= path_x1_m <= 1000 m')
    call g%add('path_points', d%path_points, range='0 <= path_points <= 10000 (0: no path)')
  end subroutine load_group

  !> Read and check the &load group of `path` (absent: no loads); `vehicle_given`: the file
  !> has &vehicle, whose axles will be the live loads the path moves.
  subroutine read_load_config(path, d, status, vehicle_given)
    character(len=*), intent(in) :: path
    type(load_config_t), intent(out), target :: d
    type(status_t), intent(inout) :: status
    logical, intent(in), optional :: vehicle_given
    type(nml_group_t) :: g
    integer :: j

    if (.not. status%ok) return
    call load_group(d, g)
    call g%read(path, status)
    if (.not. status%ok) return
    d%n_point_loads = g%length('point_load_n', path, status)
    d%n_axles = g%length('axle_spacing_m', path, status)
    do j = 1, size(d%point_load_n)   ! NaN and Infinity first, in the project's words
      if (.not. status%ok) return
      call need_finite('point_load_n('//itoa(j)//')', d%point_load_n(j))
      call need_finite('point_load_dir_deg('//itoa(j)//')', d%point_load_dir_deg(j))
      call need_finite('point_load_x_m('//itoa(j)//')', d%point_load_x_m(j))
      call need_finite('point_load_y_m('//itoa(j)//')', d%point_load_y_m(j))
      call need_finite('point_load_patch_m('//itoa(j)//')', d%point_load_patch_m(j))
    end do
    do j = 1, size(d%axle_spacing_m)
      call need_finite('axle_spacing_m('//itoa(j)//')', d%axle_spacing_m(j))
    end do
    call need_finite('dead_load_n_per_m', d%dead_load_n_per_m)
    call need_finite('dead_load_x0_m', d%dead_load_x0_m)
    call need_finite('dead_load_x1_m', d%dead_load_x1_m)
    call need_finite('path_x0_m', d%path_x0_m)
    call need_finite('path_x1_m', d%path_x1_m)
    if (.not. status%ok) return
    call g%check(path, status)
    if (.not. status%ok) return
    do j = d%n_point_loads + 1, size(d%point_load_n)
      if (d%point_load_x_m(j) /= 0.0_dp .or. d%point_load_y_m(j) /= 0.0_dp .or. &
          d%point_load_dir_deg(j) /= default_dir_deg .or. .not. d%point_load_live(j) .or. &
          d%point_load_patch_m(j) /= 0.0_dp .or. d%point_load_case(j) /= 0) then
        call fail(status, path//': &load point load '//itoa(j)//' has a point, a direction, a kind, a patch or a case but no '// &
                  'magnitude: '// &
                  'set point_load_n('//itoa(j)//') > 0 [N]')
        return
      end if
    end do
    do j = 1, d%n_point_loads   ! a patch is a live load on the top surface, straight down
      if (.not. status%ok) return
      if (d%point_load_patch_m(j) == 0.0_dp) cycle
      call need(d%point_load_live(j) .and. d%point_load_dir_deg(j) == default_dir_deg, path, 'load', &
                'point_load_patch_m('//itoa(j)//')', d%point_load_patch_m(j), 'point_load_patch_m = 0 for a dead '// &
                'load or one not straight down (a patch is a live load standing on the top surface or the '// &
                "fill's, point_load_dir_deg = -90)", status)
    end do
    call need(d%dead_load_n_per_m == 0.0_dp .or. d%dead_load_x1_m > d%dead_load_x0_m, path, 'load', &
              'dead_load_x1_m', d%dead_load_x1_m, 'dead_load_x1_m > dead_load_x0_m = '//fmt_real(d%dead_load_x0_m)// &
              ' m where dead_load_n_per_m > 0', status)
    call need(d%path_points /= 1, path, 'load', 'path_points', d%path_points, &
              'path_points = 0 (no path) or path_points >= 2', status)
    if (d%path_points >= 2) then
      call need(d%path_x1_m > d%path_x0_m, path, 'load', 'path_x1_m', d%path_x1_m, &
                'path_x1_m > path_x0_m = '//fmt_real(d%path_x0_m)//' m', status)
    end if
    if (present(vehicle_given)) then
      if (vehicle_given) return
    end if
    if (status%ok .and. (d%path_points >= 2 .or. d%n_axles > 0) .and. &
        .not. any(d%point_load_live(1:d%n_point_loads))) &
      call fail(status, path//': &load '//trim(merge('path_points   ', 'axle_spacing_m', d%path_points >= 2))// &
                ' moves or repeats the live point loads, but no point load is live: give one with '// &
                'point_load_n(j) > 0 and point_load_live(j) = .true.')

  contains

    subroutine need_finite(name, x)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: x
      if (.not. status%ok) return
      if (x /= x .or. abs(x) > huge(x)) &
        call fail(status, path//': &load '//name//' = '//trim(fmt_real(x))//' is not a finite number')
    end subroutine need_finite

  end subroutine read_load_config

  !> The effective settings of &load: the point loads given (not the empty entries).
  function load_entries(d) result(e)
    type(load_config_t), intent(in) :: d
    type(config_entry_t), allocatable :: e(:)
    type(load_config_t), target :: c
    type(nml_group_t) :: g
    integer :: k, j, open
    logical, allocatable :: keep(:)
    c = d
    call load_group(c, g)
    e = g%entries()
    allocate (keep(size(e)))
    keep = .true.
    do k = 1, size(e)
      if (e(k)%name(1:11) /= 'point_load_') cycle
      open = index(e(k)%name, '(')
      read (e(k)%name(open + 1:index(e(k)%name, ')') - 1), *) j
      keep(k) = j <= d%n_point_loads
    end do
    e = pack(e, keep)
  end function load_entries

end module voussoir_load_config
