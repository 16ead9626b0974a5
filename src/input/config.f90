!> The input of a run: namelist groups read into validated types.
!>
!> Groups: &arch, &motion, &solver, &output (and the drivers' own, e.g. &sweep and
!> &limit, which they read themselves; `check_groups` refuses any other group). Each
!> group is a table (`config_groups`: every variable once, with its unit and allowed
!> range) read by voussoir_namelist_group; a bad value gives an error that names the
!> file, the group, the variable, the value and the allowed range. `config_entries`
!> lists the effective configuration, defaults included, for the result files.
module voussoir_config
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, fmt_real, itoa
  use voussoir_namelist_check, only: check_groups
  use voussoir_namelist_group, only: nml_group_t, config_entry_t, checked_apart
  use voussoir_input_range, only: in_range
  use voussoir_wall_config, only: wall_config_t, read_wall_config, wall_group
  use voussoir_load_config, only: load_config_t, read_load_config, load_entries
  use voussoir_load_case_config, only: load_cases_t, read_load_cases, check_load_cases, case_load, load_cases_group
  use voussoir_bridge_config, only: bridge_config_t, read_bridge_config, bridge_group, bridge_length_m
  use voussoir_vehicle_config, only: vehicle_config_t, read_vehicle_config, vehicle_group, add_vehicle_loads, &
    check_on_deck
  implicit none
  private

  public :: config_t, arch_config_t, motion_config_t, solver_config_t, output_config_t
  public :: config_entry_t, read_config, validate_config, config_entries, config_to_nml
  public :: resolve_path, fmt_real, arch_rule, arch_rule_text, config_groups, has_loads, assembly_span

  !> The waveforms of &motion (the `select case` on them: validate_motion and setup).
  character(len=*), parameter, public :: waveform_afd = 'afd', waveform_ramp = 'ramp', &
    waveform_record = 'record', waveform_accelerogram = 'accelerogram'
  character(len=16), parameter, public :: waveform_names(4) = [character(len=16) :: &
    waveform_afd, waveform_ramp, waveform_record, waveform_accelerogram]
  !> &arch restrained_springings: which springing blocks are held against sliding outwards.
  character(len=*), parameter, public :: springings_none = 'none', springings_left = 'left', &
    springings_right = 'right', springings_both = 'both'
  character(len=16), parameter :: springings_names(4) = [character(len=16) :: &
    springings_none, springings_left, springings_right, springings_both]
  !> `when` of the &arch ranges that hold for the arch builder only, and for a polygon file only.
  character(len=*), parameter :: arch_builder = 'arch builder', polygon_assembly = 'polygon file'

  integer, parameter :: path_len = 512
  integer, parameter :: max_joint = 255               !! highest joint index of joint_friction
  integer, parameter :: max_voussoirs = 1000          !! beyond, a run or a limit analysis takes hours
  real(dp), parameter :: unset_friction = -huge(1.0_dp) !! a joint_friction entry left at the default

  !> &arch: the arch (or a polygon file) and its material.
  type :: arch_config_t
    real(dp) :: embrace_deg = 156.0_dp        !! total angle of embrace [deg]
    integer :: n_voussoirs = 13
    real(dp) :: r_ext_m = 0.508_dp            !! extrados radius [m]
    real(dp) :: thickness_m = 0.071_dp        !! radial thickness [m]
    real(dp) :: width_m = 0.145_dp            !! out-of-plane width [m]
    real(dp) :: density_kg_m3 = 700.0_dp
    real(dp) :: friction = 0.5_dp             !! Coulomb coefficient of every contact
    real(dp) :: contact_inset_m = 0.0_dp      !! contact points set in from face ends [m]
    character(len=16) :: restrained_springings = springings_none  !! one of springings_names
    real(dp) :: bracket_gap_m = 0.0_dp        !! play between each bracket and its voussoir [m]
    character(len=path_len) :: polygon_file = ''          !! assembly instead of an arch
    !> Coulomb coefficient of joint j (0..n_voussoirs) where set, e.g. joint_friction(0) = 0.3
    real(dp) :: joint_friction(0:max_joint) = unset_friction
    !> voussoir sizes vary by up to this fraction of the nominal angle (random pattern)
    real(dp) :: size_imperfection = 0.0_dp
    integer :: imperfection_seed = 1          !! the pattern of the size imperfection
  end type arch_config_t

  !> &motion: the base motion.
  type :: motion_config_t
    character(len=16) :: waveform = waveform_afd  !! one of waveform_names
    real(dp) :: frequency_hz = 1.25_dp
    real(dp) :: amplitude_m = 0.046_dp        !! commanded amplitude of the full cycles
    integer :: n_attack = 1, n_full = 1, n_decay = 1
    !> record: CSV with t_s, table_x_m; accelerogram: PEER .AT2 (g) or CSV with t_s, accel_m_s2
    character(len=path_len) :: record_file = ''
    real(dp) :: record_cutoff_hz = 20.0_dp    !! low-pass cut-off of the record
    real(dp) :: ramp_rate_m_s3 = 0.1_dp       !! growth of the ramp's load acceleration
    real(dp) :: lead_s = 0.0_dp               !! the table still before the motion starts [s]
    real(dp) :: rest_s = 1.0_dp               !! the table still after the motion ends [s]
    real(dp) :: duration_s = 0.0_dp           !! total simulated time; 0: motion + rest
    real(dp) :: table_gain = 1.0_dp           !! actuator model: table / commanded amplitude
    real(dp) :: table_delay_s = 0.0_dp        !! actuator model: lag of the table [s]
    real(dp) :: record_scale = 1.0_dp         !! accelerogram: factor on the acceleration (both components)
    !> accelerogram: the vertical component's record (upwards, same time steps), any format of record_file
    character(len=path_len) :: record_vertical_file = ''
    !> afd, accelerogram: vertical table acceleration / horizontal one (in phase); 0: none
    real(dp) :: vertical_ratio = 0.0_dp
    !> accelerogram: -1 plays the horizontal record with its sign reversed (the motion mirrored)
    integer :: record_polarity = 1
  end type motion_config_t

  !> &solver: time stepping and contact solve.
  type :: solver_config_t
    real(dp) :: dt_s = 1.0e-3_dp
    real(dp) :: theta = 0.5_dp
    real(dp) :: tol = 1.0e-4_dp
    integer :: max_iter = 10000
    real(dp) :: alert_m = 0.0_dp              !! 0: 2 % of the smallest free block
    logical :: allow_nonconvergence = .false.
    logical :: coarse_correction = .true.     !! walls: coarse correction of the normal impulses per course
    !> The static capacity lambda g [m/s2] below which the assembly at rest moves with the
    !> table, so that those steps are not solved (src/run/rest_window.f90; 0: every step is
    !> solved). A sweep sets it per model sample (`&sweep skip_at_rest`); a run of a sweep's
    !> row written by `voussoir-sweep --write-rows` carries it, so that it replays the row.
    real(dp) :: rest_capacity_m_s2 = 0.0_dp
  end type solver_config_t

  !> &output: the result file and the monitors.
  type :: output_config_t
    character(len=path_len) :: file = 'voussoir_run.h5'
    integer :: every = 10                     !! steps between samples
    real(dp) :: hinge_gap_m = 0.0_dp          !! 0: 1 % of the thickness
    real(dp) :: collapse_drop_m = 0.0_dp      !! 0: half the thickness
    real(dp) :: collapse_rotation_rad = 0.5_dp
    real(dp) :: stop_after_collapse_s = 0.5_dp !! < 0: run to the end
  end type output_config_t

  !> The whole input of a simulation.
  type :: config_t
    type(arch_config_t) :: arch
    type(motion_config_t) :: motion
    type(solver_config_t) :: solver
    type(output_config_t) :: output
    type(wall_config_t) :: wall               !! a wall instead of the arch, where courses > 0
    type(load_config_t) :: load               !! point, axle and distributed loads (&load; none: no loads)
    type(bridge_config_t) :: bridge           !! a bridge instead of the arch, where it has spans (&bridge)
    type(vehicle_config_t) :: vehicle         !! a vehicle by its axles (&vehicle): live point loads of `load`
    !> &load as the file gives it (`load` holds the vehicle's axles too): the effective
    !> settings record this one, so that they read back to the same configuration.
    type(load_config_t) :: load_given
    type(load_cases_t) :: cases               !! named load cases with partial factors (&load_cases; none: n = 0)
    character(len=path_len) :: source_file = ''
    !> What validate_config found plausible but unusual, one line each, for the drivers to
    !> print (config_plausible.f90); not a setting.
    character(len=1024) :: warnings = ''
  end type config_t

  !> Check every value of `cfg` against its physical range (config_validate.f90).
  interface
    module subroutine validate_config(cfg, status)
      type(config_t), intent(inout), target :: cfg
      type(status_t), intent(inout) :: status
    end subroutine validate_config
    !> The arch builder's ring against the sizes of real masonry arches (config_plausible.f90).
    module subroutine check_plausible_arch(cfg, f, status)
      type(config_t), intent(inout) :: cfg
      character(len=*), intent(in) :: f
      type(status_t), intent(inout) :: status
    end subroutine check_plausible_arch
    !> The afd motion against the assembly's span, and its table acceleration (config_plausible.f90).
    module subroutine check_plausible_motion(cfg, f, status)
      type(config_t), intent(inout) :: cfg
      character(len=*), intent(in) :: f
      type(status_t), intent(inout) :: status
    end subroutine check_plausible_motion
    !> The horizontal extent [m] of the assembly `cfg` builds (an arch's chord between
    !> its extrados ends, a wall's length) and its name in messages ("the arch's span");
    !> 0 and '' for a polygon file, whose blocks the assembly reads (config_plausible.f90).
    module subroutine assembly_span(cfg, span_m, what)
      type(config_t), intent(in) :: cfg
      real(dp), intent(out) :: span_m
      character(len=:), allocatable, intent(out) :: what
    end subroutine assembly_span
  end interface

contains

  !> Read and validate the &arch, &motion, &solver and &output groups of `path`;
  !> `allowed_groups` lists every group the calling driver accepts in the file.
  subroutine read_config(path, allowed_groups, cfg, status)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: allowed_groups(:)
    type(config_t), intent(out), target :: cfg
    type(status_t), intent(inout) :: status
    type(nml_group_t) :: groups(4)
    integer :: k
    logical :: found, arch_given

    cfg%source_file = path
    call check_groups(path, allowed_groups, status)
    if (.not. status%ok) return
    call config_groups(cfg, groups)
    arch_given = .false.
    do k = 1, size(groups)
      call groups(k)%read(path, status, found)
      if (.not. status%ok) return
      if (k == 1) arch_given = found
    end do
    if (any(allowed_groups == 'wall')) call read_wall_config(path, cfg%wall, status)
    if (any(allowed_groups == 'vehicle')) call read_vehicle_config(path, cfg%vehicle, status)
    if (any(allowed_groups == 'load')) call read_load_config(path, cfg%load, status, cfg%vehicle%given)
    if (any(allowed_groups == 'bridge')) call read_bridge_config(path, cfg%bridge, status)
    if (.not. status%ok) return
    cfg%load_given = cfg%load
    call add_vehicle_loads(cfg%vehicle, merge(cfg%bridge%width_m, cfg%arch%width_m, cfg%bridge%n_spans > 0), path, &
                           cfg%load, status)
    if (any(allowed_groups == 'load_cases')) call read_load_cases(path, cfg%cases, status)
    call check_load_cases(cfg%cases, cfg%load, path, status)
    if (cfg%cases%n == 0) call check_on_deck(cfg%bridge, cfg%load, cfg%vehicle, path, status)
    if (.not. status%ok) return
    do k = 1, cfg%cases%n   ! each case's live loads move about their own resultant
      call check_on_deck(cfg%bridge, case_load(cfg%load, cfg%cases, k), cfg%vehicle, path, status)
      if (.not. status%ok) status%message = trim(status%message)//' (load case '//itoa(k)//')'
      if (.not. status%ok) return
    end do
    if (cfg%bridge%n_spans > 0) then
      if (arch_given) then
        call fail(status, path//': &bridge and &arch both describe the assembly: give one of them (&bridge has '// &
                  'its own width_m, the density and friction of each part; &limit inset_m the pivot inset)')
        return
      end if
      ! The ring's material and size where a driver reads the run's (the other parts carry
      ! their own in the assembly).
      cfg%arch%width_m = cfg%bridge%width_m
      cfg%arch%density_kg_m3 = cfg%bridge%ring_density_kg_m3
      cfg%arch%friction = cfg%bridge%ring_friction
      cfg%arch%thickness_m = cfg%bridge%ring_thickness_m
    end if
    if (len_trim(cfg%arch%polygon_file) > 0) &
      cfg%arch%polygon_file = resolve_path(path, cfg%arch%polygon_file)
    if (len_trim(cfg%motion%record_file) > 0) &
      cfg%motion%record_file = resolve_path(path, cfg%motion%record_file)
    if (len_trim(cfg%motion%record_vertical_file) > 0) &
      cfg%motion%record_vertical_file = resolve_path(path, cfg%motion%record_vertical_file)
    call validate_config(cfg, status)
  end subroutine read_config

  !> The tables of &arch, &motion, &solver and &output over `cfg`, in the order of the
  !> effective settings: each variable once, with its unit and its own allowed range.
  !> A range with `when` holds in one case only (validate_config asks for it there).
  subroutine config_groups(cfg, groups)
    type(config_t), intent(inout), target :: cfg
    type(nml_group_t), intent(out) :: groups(4)
    call arch_group(cfg%arch, groups(1))
    associate (m => cfg%motion, g => groups(2))
      g%name = 'motion'
      call g%add('waveform', m%waveform, choices=waveform_names)
      call g%add('frequency_hz', m%frequency_hz, unit='Hz', range='frequency_hz > 0', when=waveform_afd)
      call g%add('amplitude_m', m%amplitude_m, unit='m', range='amplitude_m >= 0', when=waveform_afd)
      call g%add('n_attack', m%n_attack, range='n_attack >= 1', when=waveform_afd)
      call g%add('n_full', m%n_full, range='n_full >= 0', when=waveform_afd)
      call g%add('n_decay', m%n_decay, range='n_decay >= 1', when=waveform_afd)
      call g%add('record_file', m%record_file)
      call g%add('record_cutoff_hz', m%record_cutoff_hz, unit='Hz', range='record_cutoff_hz >= 0 (0: no filter)', &
                 when=waveform_record)
      call g%add('ramp_rate_m_s3', m%ramp_rate_m_s3, unit='m/s3', range='ramp_rate_m_s3 /= 0', when=waveform_ramp)
      call g%add('lead_s', m%lead_s, unit='s', range='lead_s >= 0')
      call g%add('rest_s', m%rest_s, unit='s', range='rest_s >= 0')
      call g%add('duration_s', m%duration_s, unit='s', range='duration_s >= 0')
      call g%add('table_gain', m%table_gain, range='table_gain > 0', when=waveform_afd)
      call g%add('table_delay_s', m%table_delay_s, unit='s', range='table_delay_s >= 0', when=waveform_afd)
      call g%add('record_scale', m%record_scale, range='record_scale > 0 (finite)', when=waveform_accelerogram)
      call g%add('record_vertical_file', m%record_vertical_file)
      call g%add('vertical_ratio', m%vertical_ratio, range='-2 <= vertical_ratio <= 2')
      call g%add('record_polarity', m%record_polarity, range='-1 <= record_polarity <= 1 (1 or -1)', &
                 when=checked_apart)
    end associate
    associate (s => cfg%solver, g => groups(3))
      g%name = 'solver'
      call g%add('dt_s', s%dt_s, unit='s', range='0 < dt_s <= 0.1')
      call g%add('theta', s%theta, range='0.5 <= theta <= 1')
      call g%add('tol', s%tol, range='0 < tol < 1')
      call g%add('max_iter', s%max_iter, range='max_iter >= 1')
      call g%add('alert_m', s%alert_m, unit='m', range='alert_m >= 0 (0: automatic)')
      call g%add('allow_nonconvergence', s%allow_nonconvergence)
      call g%add('coarse_correction', s%coarse_correction)
      call g%add('rest_capacity_m_s2', s%rest_capacity_m_s2, unit='m/s2', &
                 range='rest_capacity_m_s2 >= 0 (0: every step is solved)')
    end associate
    associate (o => cfg%output, g => groups(4))
      g%name = 'output'
      call g%add('file', o%file)
      call g%add('every', o%every, range='every >= 1')
      call g%add('hinge_gap_m', o%hinge_gap_m, unit='m', range='hinge_gap_m >= 0')
      call g%add('collapse_drop_m', o%collapse_drop_m, unit='m', range='collapse_drop_m >= 0')
      call g%add('collapse_rotation_rad', o%collapse_rotation_rad, unit='rad', range='collapse_rotation_rad > 0')
      call g%add('stop_after_collapse_s', o%stop_after_collapse_s, unit='s')
    end associate
  end subroutine config_groups

  !> The &arch table: the ranges of the arch's shape hold for the arch builder, the
  !> thickness's own range for a polygon file (an arch's is below r_ext_m).
  subroutine arch_group(a, g)
    type(arch_config_t), intent(inout), target :: a
    type(nml_group_t), intent(out) :: g
    g%name = 'arch'
    call g%add('embrace_deg', a%embrace_deg, unit='deg', range='0 < embrace_deg <= 180', when=arch_builder)
    call g%add('n_voussoirs', a%n_voussoirs, range='2 <= n_voussoirs <= '//itoa(max_voussoirs), when=arch_builder)
    call g%add('r_ext_m', a%r_ext_m, unit='m', range='0 < r_ext_m <= 1000 m', when=arch_builder)
    call g%add('thickness_m', a%thickness_m, unit='m', range='0 < thickness_m <= 1000 m', when=polygon_assembly)
    call g%add('width_m', a%width_m, unit='m', range='0 < width_m <= 1000 m')
    call g%add('density_kg_m3', a%density_kg_m3, unit='kg/m3', range='0 < density_kg_m3 <= 1e5')
    call g%add('friction', a%friction, range='friction >= 0 (finite)')
    call g%add('contact_inset_m', a%contact_inset_m, unit='m', range='contact_inset_m >= 0 (finite)', &
               when=checked_apart)
    call g%add('restrained_springings', a%restrained_springings, choices=springings_names, when=arch_builder)
    call g%add('bracket_gap_m', a%bracket_gap_m, unit='m', range='bracket_gap_m >= 0 (finite)', when=arch_builder)
    call g%add('polygon_file', a%polygon_file)
    call g%add('joint_friction', a%joint_friction, first=0, unset=unset_friction, range='joint_friction >= 0', &
               about='real, the friction of joint j = 0..n_voussoirs')
    call g%add('size_imperfection', a%size_imperfection, range='0 <= size_imperfection < 0.5')
    call g%add('imperfection_seed', a%imperfection_seed, range='imperfection_seed >= 0')
  end subroutine arch_group

  !> Whether `value` of the &arch variable `name` is in its own range (the range of the
  !> &arch table, which does not depend on other variables): the one rule for &arch
  !> and the sweep's lists. A variable without a range has no rule (.false.).
  logical function arch_rule(name, value)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: value
    type(arch_config_t), target :: a
    type(nml_group_t) :: g
    integer :: k
    call arch_group(a, g)
    k = g%find(name)
    arch_rule = .false.
    if (k == 0) return
    if (len(g%vars(k)%range%text) > 0) arch_rule = in_range(g%vars(k)%range, value)
  end function arch_rule

  !> The range `arch_rule` checks, as text for messages.
  function arch_rule_text(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    type(arch_config_t), target :: a
    type(nml_group_t) :: g
    integer :: k
    call arch_group(a, g)
    k = g%find(name)
    text = trim(name)//' > 0 (finite)'
    if (k == 0) return
    if (len(g%vars(k)%range%text) > 0) text = g%vars(k)%range%text
  end function arch_rule_text
  !> A file named in an input file: absolute, or relative to that input file's folder.
  function resolve_path(input_path, name) result(full)
    character(len=*), intent(in) :: input_path, name
    character(len=path_len) :: full
    integer :: k
    full = adjustl(name)
    if (full(1:1) == '/') return
    k = index(input_path, '/', back=.true.)
    if (k > 0) full = input_path(:k)//trim(full)
  end function resolve_path

  !> Every setting of `cfg`, defaults included, in group order (the wall's or the bridge's
  !> where it has one).
  function config_entries(cfg) result(e)
    type(config_t), intent(in) :: cfg
    type(config_entry_t), allocatable :: e(:)
    type(config_t), target :: c
    type(nml_group_t) :: groups(4), wall, bridge, vehicle, cases
    c = cfg
    call config_groups(c, groups)
    e = [groups(1)%entries(), groups(2)%entries(), groups(3)%entries(), groups(4)%entries()]
    if (c%wall%courses > 0) then
      call wall_group(c%wall, wall)
      e = [e, wall%entries()]
    end if
    if (c%bridge%n_spans > 0) then
      call bridge_group(c%bridge, bridge)
      e = [e, bridge%entries()]
    end if
    if (has_loads(c) .and. .not. c%vehicle%given) e = [e, load_entries(c%load)]
    if (c%vehicle%given) then
      ! &load as given (the vehicle's axles are &vehicle's), then the vehicle.
      e = [e, load_entries(c%load_given)]
      call vehicle_group(c%vehicle, vehicle)
      e = [e, vehicle%entries()]
    end if
    if (c%cases%n > 0) then
      call load_cases_group(c%cases, cases)
      e = [e, cases%entries()]
    end if
  end function config_entries

  !> Whether &load gives any load (else the live load is the horizontal acceleration).
  pure logical function has_loads(cfg)
    type(config_t), intent(in) :: cfg
    has_loads = cfg%load%n_point_loads > 0 .or. cfg%load%dead_load_n_per_m > 0.0_dp
  end function has_loads

  !> The entries as namelist text that reads back to the same configuration.
  function config_to_nml(e) result(text)
    type(config_entry_t), intent(in) :: e(:)
    character(len=:), allocatable :: text
    integer :: k
    character(len=1), parameter :: nl = achar(10)
    text = ''
    do k = 1, size(e)
      if (k == 1) then
        text = text//'&'//trim(e(k)%group)//nl
      else if (e(k)%group /= e(k - 1)%group) then
        text = text//'/'//nl//'&'//trim(e(k)%group)//nl
      end if
      if (e(k)%kind == 's') then
        text = text//'  '//trim(e(k)%name)//" = '"//trim(e(k)%value)//"'"//nl
      else
        text = text//'  '//trim(e(k)%name)//' = '//trim(e(k)%value)//nl
      end if
    end do
    if (size(e) > 0) text = text//'/'//nl
  end function config_to_nml

end module voussoir_config
