!> The &vehicle group: a vehicle by its axles (loads in kN, the spacings between them in
!> m), user-defined or one of a few named ones whose axle data are cited in
!> docs/bridges.md ("Vehicles"). Input only: the axles become live point loads of &load
!> (add_vehicle_loads), which the limit analysis moves along &load's path as any live
!> loads (the critical position, refined at the joints; with a fill each axle spread
!> through it). check_on_deck refuses live loads that a path or their own x puts off a
!> bridge's deck, naming the variable and its value.
module voussoir_vehicle_config
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_significant, lower
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_input_range, only: need
  use voussoir_load_config, only: load_config_t, max_point_loads
  use voussoir_bridge_config, only: bridge_config_t, bridge_length_m
  implicit none
  private
  public :: vehicle_config_t, vehicle_group, read_vehicle_config, add_vehicle_loads, check_on_deck
  public :: max_vehicle_axles, vehicle_names

  integer, parameter :: max_vehicle_axles = 10
  real(dp), parameter :: unset_spacing_m = -1.0_dp     !! a spacing not given (0 is a spacing)
  !> The named vehicles (docs/bridges.md, "Vehicles", cites each one's axle data).
  character(len=*), parameter :: lm1_tandem_lane1 = 'lm1_tandem_lane1'
  character(len=32), parameter :: vehicle_names(1) = [character(len=32) :: lm1_tandem_lane1]

  !> &vehicle (absent: no vehicle).
  type :: vehicle_config_t
    character(len=32) :: name = ''                                    !! one of vehicle_names, or a label
    real(dp) :: axle_load_kn(max_vehicle_axles) = 0.0_dp              !! axle k's load [kN]; 0: no axle
    real(dp) :: axle_spacing_m(max_vehicle_axles - 1) = unset_spacing_m  !! from axle k to axle k+1 [m]
    !> The width of barrel [m] one axle spreads over (the assessor's choice): the analysed
    !> strip (&bridge width_m) carries axle load x width_m/effective_width_m; 0: the whole axle.
    real(dp) :: effective_width_m = 0.0_dp
    real(dp) :: first_axle_x_m = 0.0_dp     !! where the first axle stands when no path moves it [m]
    !> Each axle spread uniformly over this length along x (its tyres' contact) [m]; 0: a point
    real(dp) :: patch_length_m = 0.0_dp
    integer :: n_axles = 0                  !! (derived) the axles given
    logical :: given = .false.              !! (derived) the file has &vehicle
  end type vehicle_config_t

contains

  !> The &vehicle table over `v`.
  subroutine vehicle_group(v, g)
    type(vehicle_config_t), intent(inout), target :: v
    type(nml_group_t), intent(out) :: g
    g%name = 'vehicle'
    call g%add('name', v%name)
    call g%add('axle_load_kn', v%axle_load_kn, unset=0.0_dp, unit='kN', range='0 < axle_load_kn <= 1e5 kN', &
               about='real, kN, the load of axle k (the whole axle, across the barrel)')
    call g%add('axle_spacing_m', v%axle_spacing_m, unset=unset_spacing_m, unit='m', &
               range='0 <= axle_spacing_m <= 100 m', about='real, m, from axle k to axle k+1')
    call g%add('effective_width_m', v%effective_width_m, unit='m', range='0 <= effective_width_m <= 1000 m', &
               about='real, m, the barrel width one axle spreads over (0: the whole axle on the strip)')
    call g%add('first_axle_x_m', v%first_axle_x_m, unit='m', range='-1000 <= first_axle_x_m <= 1000 m', &
               about='real, m, the first axle where no path moves the vehicle (voussoir-run)')
    call g%add('patch_length_m', v%patch_length_m, unit='m', range='0 <= patch_length_m <= 10 m', &
               about='real, m, the length along x each axle is spread over, its tyres'' contact (0: a point)')
  end subroutine vehicle_group

  !> Read and check the &vehicle group of `path` (absent: no vehicle). A named vehicle
  !> fills its axles (given ones must be its own, so that the effective settings read back).
  subroutine read_vehicle_config(path, v, status)
    character(len=*), intent(in) :: path
    type(vehicle_config_t), intent(out), target :: v
    type(status_t), intent(inout) :: status
    type(nml_group_t) :: g
    real(dp), allocatable :: loads_kn(:), spacings_m(:)
    integer :: n_spacings

    if (.not. status%ok) return
    call vehicle_group(v, g)
    call g%read(path, status, v%given)
    if (.not. status%ok .or. .not. v%given) return
    v%n_axles = g%length('axle_load_kn', path, status)
    n_spacings = g%length('axle_spacing_m', path, status)
    if (.not. status%ok) return
    call g%check(path, status)
    if (.not. status%ok) return
    if (named_axles(v%name, loads_kn, spacings_m)) then
      if (v%n_axles > 0 .or. n_spacings > 0) then
        if (v%n_axles /= size(loads_kn) .or. n_spacings /= size(spacings_m)) then
          call mismatch()
          return
        end if
        if (any(v%axle_load_kn(1:v%n_axles) /= loads_kn) .or. any(v%axle_spacing_m(1:n_spacings) /= spacings_m)) then
          call mismatch()
          return
        end if
      end if
      v%n_axles = size(loads_kn)
      v%axle_load_kn(1:v%n_axles) = loads_kn
      v%axle_spacing_m(1:size(spacings_m)) = spacings_m
      return
    end if
    if (v%n_axles == 0) then
      call fail(status, path//": &vehicle name = '"//trim(v%name)//"' is not a named vehicle ("// &
                trim(names_text())//') and gives no axles: set axle_load_kn(1..n) [kN] and axle_spacing_m(1..n-1) '// &
                '[m], or name one of those')
      return
    end if
    if (n_spacings /= v%n_axles - 1) call fail(status, path//': &vehicle gives '//itoa(v%n_axles)// &
      ' axles (axle_load_kn) and '//itoa(n_spacings)//' spacings (axle_spacing_m): give '//itoa(v%n_axles - 1)// &
      ', axle_spacing_m(k) from axle k to axle k+1 [m]')

  contains

    subroutine mismatch()
      call fail(status, path//": &vehicle name = '"//trim(v%name)//"' is a named vehicle with its own axles; "// &
                'leave axle_load_kn and axle_spacing_m out, or give another name to your own axle set')
    end subroutine mismatch

  end subroutine read_vehicle_config

  !> The axles of the named vehicle `name` (.false. if it is not one): EN 1991-2 Load
  !> Model 1's tandem system on lane 1, two axles of 300 kN 1.2 m apart (docs/bridges.md).
  logical function named_axles(name, loads_kn, spacings_m)
    character(len=*), intent(in) :: name
    real(dp), allocatable, intent(out) :: loads_kn(:), spacings_m(:)
    named_axles = .true.
    select case (lower(trim(name)))
    case (lm1_tandem_lane1)
      loads_kn = [300.0_dp, 300.0_dp]
      spacings_m = [1.2_dp]
    case default
      named_axles = .false.
    end select
  end function named_axles

  function names_text() result(text)
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, size(vehicle_names)
      if (k > 1) text = text//', '
      text = text//"'"//trim(vehicle_names(k))//"'"
    end do
  end function names_text

  !> The axles of `v` as live point loads of `d` (straight down; on the strip of `width_m`:
  !> axle load x width_m/effective_width_m), the first at first_axle_x_m and each next one
  !> axle_spacing_m further along +x. The vehicle is the live load: &load may give dead
  !> point loads beside it, and the path that moves it.
  subroutine add_vehicle_loads(v, width_m, path, d, status)
    type(vehicle_config_t), intent(in) :: v
    real(dp), intent(in) :: width_m
    character(len=*), intent(in) :: path
    type(load_config_t), intent(inout) :: d
    type(status_t), intent(inout) :: status
    real(dp) :: share, x
    integer :: k, j

    if (.not. status%ok .or. .not. v%given) return
    if (any(d%point_load_live(1:d%n_point_loads))) then
      call fail(status, path//': &vehicle and a live point load of &load: the vehicle is the live load; make '// &
                "&load's point loads dead (point_load_live(j) = .false.) or leave &vehicle out")
      return
    end if
    if (d%n_axles > 0) then
      call fail(status, path//': &vehicle and &load axle_spacing_m: give the axles in &vehicle alone')
      return
    end if
    if (d%path_points < 2) then
      call fail(status, path//': &vehicle needs a &load path to move it over (path_x0_m, path_x1_m, path_points '// &
                '>= 2): the load factor is found at its critical position')
      return
    end if
    call need(v%effective_width_m == 0.0_dp .or. v%effective_width_m >= width_m, path, 'vehicle', &
              'effective_width_m', v%effective_width_m, '0 (the whole axle on the strip) or effective_width_m >= '// &
              'width_m = '//fmt_significant(width_m, 6)//' m (the strip analysed carries at most the whole axle)', &
              status)
    if (d%n_point_loads + v%n_axles > max_point_loads) call fail(status, path//': &vehicle gives '// &
      itoa(v%n_axles)//' axles (axle_load_kn) beside the '//itoa(d%n_point_loads)//' point loads of &load: at '// &
      'most '//itoa(max_point_loads)//' point loads in all')
    if (.not. status%ok) return
    share = 1.0_dp
    if (v%effective_width_m > 0.0_dp) share = width_m/v%effective_width_m
    x = v%first_axle_x_m
    do k = 1, v%n_axles
      if (k > 1) x = x + v%axle_spacing_m(k - 1)
      j = d%n_point_loads + k
      d%point_load_n(j) = 1.0e3_dp*v%axle_load_kn(k)*share
      d%point_load_dir_deg(j) = -90.0_dp
      d%point_load_x_m(j) = x
      d%point_load_y_m(j) = 0.0_dp
      d%point_load_live(j) = .true.
      d%point_load_patch_m(j) = v%patch_length_m
    end do
    d%n_point_loads = d%n_point_loads + v%n_axles
  end subroutine add_vehicle_loads

  !> The live loads of `d` that move on the top surface (an axle group or a path) stay on
  !> the deck of the bridge `b`, from the back of its left abutment to the back of its
  !> right one: at both ends of the path, or where they stand without one. The refusal
  !> names the path's end (or the load's x) and its value, the axles' extent and the deck's.
  subroutine check_on_deck(b, d, v, path, status)
    type(bridge_config_t), intent(in) :: b
    type(load_config_t), intent(in) :: d
    type(vehicle_config_t), intent(in) :: v
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    real(dp) :: deck_lo, deck_hi, lo, hi, resultant, total
    real(dp), parameter :: tol_m = 1.0e-9_dp
    integer :: j, a

    if (.not. status%ok .or. b%n_spans == 0 .or. .not. (d%n_axles > 0 .or. d%path_points >= 2)) return
    deck_lo = -b%abutment_width_m
    deck_hi = bridge_length_m(b) - b%abutment_width_m
    ! The axles' extent and their resultant's x as given (no shift).
    lo = huge(1.0_dp)
    hi = -huge(1.0_dp)
    resultant = 0.0_dp
    total = 0.0_dp
    do j = 1, d%n_point_loads
      if (.not. d%point_load_live(j)) cycle
      do a = 0, d%n_axles   ! a patch reaches half its length either side
        lo = min(lo, axle_x(j, a) - 0.5_dp*d%point_load_patch_m(j))
        hi = max(hi, axle_x(j, a) + 0.5_dp*d%point_load_patch_m(j))
        resultant = resultant + d%point_load_n(j)*axle_x(j, a)
        total = total + d%point_load_n(j)
      end do
    end do
    if (total <= 0.0_dp) return
    resultant = resultant/total
    if (d%path_points >= 2) then
      ! The path moves the resultant: the axles reach resultant - lo behind it, hi - resultant ahead.
      call need(d%path_x0_m - (resultant - lo) >= deck_lo - tol_m, path, 'load', 'path_x0_m', d%path_x0_m, &
                'path_x0_m >= '//fmt_significant(deck_lo + resultant - lo, 6)//' m: there the '//what()// &
                ' reaches back to x = '//fmt_significant(d%path_x0_m - (resultant - lo), 6)//' m, off the deck '// &
                '(the bridge runs from x = '//fmt_significant(deck_lo, 6)//' to '//fmt_significant(deck_hi, 6)// &
                ' m, the backs of its abutments)', status)
      call need(d%path_x1_m + (hi - resultant) <= deck_hi + tol_m, path, 'load', 'path_x1_m', d%path_x1_m, &
                'path_x1_m <= '//fmt_significant(deck_hi - (hi - resultant), 6)//' m: there the '//what()// &
                ' reaches to x = '//fmt_significant(d%path_x1_m + (hi - resultant), 6)//' m, off the deck '// &
                '(the bridge runs from x = '//fmt_significant(deck_lo, 6)//' to '//fmt_significant(deck_hi, 6)// &
                ' m, the backs of its abutments)', status)
    end if
    ! Where the loads stand without a path (voussoir-run's vehicle, always).
    if (v%given) then
      call need(lo >= deck_lo - tol_m .and. hi <= deck_hi + tol_m, path, 'vehicle', 'first_axle_x_m', &
                v%first_axle_x_m, fmt_significant(deck_lo + (v%first_axle_x_m - lo), 6)// &
                ' m <= first_axle_x_m <= '//fmt_significant(deck_hi - (hi - v%first_axle_x_m), 6)// &
                ' m: its axles stand from x = '//fmt_significant(lo, 6)// &
                ' to '//fmt_significant(hi, 6)//' m, off the deck (the bridge runs from x = '// &
                fmt_significant(deck_lo, 6)//' to '//fmt_significant(deck_hi, 6)//' m, the backs of its abutments; '// &
                'voussoir-run stands the vehicle there)', status)
    else if (d%path_points < 2 .and. (lo < deck_lo - tol_m .or. hi > deck_hi + tol_m)) then
      call fail(status, path//': &load live point loads with axle_spacing_m stand from x = '// &
                fmt_significant(lo, 6)//' to '//fmt_significant(hi, 6)//' m, off the deck (the bridge runs from '// &
                'x = '//fmt_significant(deck_lo, 6)//' to '//fmt_significant(deck_hi, 6)//' m): move '// &
                'point_load_x_m in')
    end if

  contains

    pure real(dp) function axle_x(j, a)
      integer, intent(in) :: j, a
      axle_x = d%point_load_x_m(j)
      if (a > 0) axle_x = axle_x + d%axle_spacing_m(a)
    end function axle_x

    function what() result(text)
      character(len=:), allocatable :: text
      text = 'live load'
      if (v%given) text = 'vehicle ('//itoa(v%n_axles)//' axles over '//fmt_significant(hi - lo, 6)//' m)'
    end function what

  end subroutine check_on_deck

end module voussoir_vehicle_config
