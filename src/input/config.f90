!> The input of a run: namelist groups read into validated types.
!>
!> Groups: &arch, &motion, &solver, &output (and the drivers' own, e.g. &sweep and
!> &limit, which they read themselves; `check_groups` refuses any other group). Every value is
!> checked; a bad one gives an error that names the file, the group, the variable, the
!> value and the allowed range. `config_entries` lists the effective configuration,
!> defaults included, for the result files.
module voussoir_config
  use, intrinsic :: iso_fortran_env, only: iostat_end
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, fmt_real, itoa
  use voussoir_namelist_check, only: check_groups, check_names
  use voussoir_wall_config, only: wall_config_t, read_wall_config
  implicit none
  private

  public :: config_t, arch_config_t, motion_config_t, solver_config_t, output_config_t
  public :: config_entry_t, read_config, validate_config, config_entries, config_to_nml
  public :: resolve_path, fmt_real, arch_rule, arch_rule_text

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
    character(len=16) :: restrained_springings = 'none'  !! none, left, right, both
    character(len=path_len) :: polygon_file = ''          !! assembly instead of an arch
    !> Coulomb coefficient of joint j (0..n_voussoirs) where set, e.g. joint_friction(0) = 0.3
    real(dp) :: joint_friction(0:max_joint) = unset_friction
    !> voussoir sizes vary by up to this fraction of the nominal angle (random pattern)
    real(dp) :: size_imperfection = 0.0_dp
    integer :: imperfection_seed = 1          !! the pattern of the size imperfection
  end type arch_config_t

  !> &motion: the base motion.
  type :: motion_config_t
    character(len=16) :: waveform = 'afd'     !! afd, ramp, record or accelerogram
    real(dp) :: frequency_hz = 1.25_dp
    real(dp) :: amplitude_m = 0.046_dp        !! commanded amplitude of the full cycles
    integer :: n_attack = 1, n_full = 1, n_decay = 1
    !> record: CSV with t_s, table_x_m; accelerogram: PEER .AT2 (g) or CSV with t_s, accel_m_s2
    character(len=path_len) :: record_file = ''
    real(dp) :: record_cutoff_hz = 20.0_dp    !! low-pass cut-off of the record
    real(dp) :: ramp_rate_m_s3 = 0.1_dp       !! growth of the ramp's load acceleration
    !> simulated time after the motion ends; accelerogram: time at rest before its first sample
    real(dp) :: rest_s = 1.0_dp
    real(dp) :: duration_s = 0.0_dp           !! total simulated time; 0: motion + rest
    real(dp) :: table_gain = 1.0_dp           !! actuator model: table / commanded amplitude
    real(dp) :: table_delay_s = 0.0_dp        !! actuator model: lag of the table [s]
    real(dp) :: record_scale = 1.0_dp         !! accelerogram: factor on the acceleration
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
    character(len=path_len) :: source_file = ''
  end type config_t

  !> One effective setting: group, name, type ('r', 'i', 'l', 's') and value as text.
  type :: config_entry_t
    character(len=16) :: group = ''
    character(len=32) :: name = ''
    character(len=1) :: kind = 's'
    character(len=path_len) :: value = ''
  end type config_entry_t

  !> Check every value of `cfg` against its physical range (config_validate.f90).
  interface
    module subroutine validate_config(cfg, status)
      type(config_t), intent(inout) :: cfg
      type(status_t), intent(inout) :: status
    end subroutine validate_config
  end interface

contains

  !> Read and validate the &arch, &motion, &solver and &output groups of `path`;
  !> `allowed_groups` lists every group the calling driver accepts in the file.
  subroutine read_config(path, allowed_groups, cfg, status)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: allowed_groups(:)
    type(config_t), intent(out) :: cfg
    type(status_t), intent(inout) :: status
    integer :: unit, ios
    character(len=512) :: iomsg
    ! Namelist objects, initialised from the defaults of the types.
    type(arch_config_t) :: a
    type(motion_config_t) :: m
    type(solver_config_t) :: s
    type(output_config_t) :: o
    real(dp) :: embrace_deg, r_ext_m, thickness_m, width_m, density_kg_m3, friction, contact_inset_m
    real(dp) :: joint_friction(0:max_joint), size_imperfection
    integer :: n_voussoirs, imperfection_seed
    character(len=16) :: restrained_springings, waveform
    character(len=path_len) :: polygon_file, record_file, file
    real(dp) :: frequency_hz, amplitude_m, record_cutoff_hz, ramp_rate_m_s3, rest_s, duration_s, &
                table_gain, table_delay_s, record_scale
    integer :: n_attack, n_full, n_decay, max_iter, every
    real(dp) :: dt_s, theta, tol, alert_m, hinge_gap_m, collapse_drop_m, collapse_rotation_rad, &
                stop_after_collapse_s
    logical :: allow_nonconvergence, coarse_correction
    namelist /arch/ embrace_deg, n_voussoirs, r_ext_m, thickness_m, width_m, density_kg_m3, &
      friction, contact_inset_m, restrained_springings, polygon_file, joint_friction, size_imperfection, &
      imperfection_seed
    namelist /motion/ waveform, frequency_hz, amplitude_m, n_attack, n_full, n_decay, &
      record_file, record_cutoff_hz, ramp_rate_m_s3, rest_s, duration_s, table_gain, table_delay_s, &
      record_scale
    namelist /solver/ dt_s, theta, tol, max_iter, alert_m, allow_nonconvergence, coarse_correction
    namelist /output/ file, every, hinge_gap_m, collapse_drop_m, collapse_rotation_rad, &
      stop_after_collapse_s

    cfg%source_file = path
    call check_groups(path, allowed_groups, status)
    if (.not. status%ok) return
    open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, trim(path)//': cannot open input: '//trim(iomsg))
      return
    end if

    embrace_deg = a%embrace_deg; n_voussoirs = a%n_voussoirs; r_ext_m = a%r_ext_m
    thickness_m = a%thickness_m; width_m = a%width_m; density_kg_m3 = a%density_kg_m3
    friction = a%friction; contact_inset_m = a%contact_inset_m
    restrained_springings = a%restrained_springings; polygon_file = a%polygon_file
    joint_friction = a%joint_friction
    size_imperfection = a%size_imperfection; imperfection_seed = a%imperfection_seed
    call check_names(path, 'arch', [character(len=24) :: 'embrace_deg', 'n_voussoirs', 'r_ext_m', &
      'thickness_m', 'width_m', 'density_kg_m3', 'friction', 'contact_inset_m', 'restrained_springings', &
      'polygon_file', 'joint_friction', 'size_imperfection', 'imperfection_seed'], status)
    call check_names(path, 'motion', [character(len=24) :: 'waveform', 'frequency_hz', 'amplitude_m', &
      'n_attack', 'n_full', 'n_decay', 'record_file', 'record_cutoff_hz', 'ramp_rate_m_s3', 'rest_s', &
      'duration_s', 'table_gain', 'table_delay_s', 'record_scale'], status)
    call check_names(path, 'solver', [character(len=24) :: 'dt_s', 'theta', 'tol', 'max_iter', 'alert_m', &
      'allow_nonconvergence', 'coarse_correction'], status)
    call check_names(path, 'output', [character(len=24) :: 'file', 'every', 'hinge_gap_m', 'collapse_drop_m', &
      'collapse_rotation_rad', 'stop_after_collapse_s'], status)
    if (.not. status%ok) then
      close (unit)
      return
    end if
    read (unit, nml=arch, iostat=ios, iomsg=iomsg)
    if (.not. group_ok('arch')) return
    a = arch_config_t(embrace_deg, n_voussoirs, r_ext_m, thickness_m, width_m, density_kg_m3, &
                      friction, contact_inset_m, restrained_springings, polygon_file, joint_friction, &
                      size_imperfection, imperfection_seed)

    waveform = m%waveform; frequency_hz = m%frequency_hz; amplitude_m = m%amplitude_m
    n_attack = m%n_attack; n_full = m%n_full; n_decay = m%n_decay; record_file = m%record_file
    record_cutoff_hz = m%record_cutoff_hz; ramp_rate_m_s3 = m%ramp_rate_m_s3; rest_s = m%rest_s
    duration_s = m%duration_s; table_gain = m%table_gain; table_delay_s = m%table_delay_s
    record_scale = m%record_scale
    rewind (unit)
    read (unit, nml=motion, iostat=ios, iomsg=iomsg)
    if (.not. group_ok('motion')) return
    m = motion_config_t(waveform, frequency_hz, amplitude_m, n_attack, n_full, n_decay, &
                        record_file, record_cutoff_hz, ramp_rate_m_s3, rest_s, duration_s, &
                        table_gain, table_delay_s, record_scale)

    dt_s = s%dt_s; theta = s%theta; tol = s%tol; max_iter = s%max_iter; alert_m = s%alert_m
    allow_nonconvergence = s%allow_nonconvergence; coarse_correction = s%coarse_correction
    rewind (unit)
    read (unit, nml=solver, iostat=ios, iomsg=iomsg)
    if (.not. group_ok('solver')) return
    s = solver_config_t(dt_s, theta, tol, max_iter, alert_m, allow_nonconvergence, coarse_correction)

    file = o%file; every = o%every; hinge_gap_m = o%hinge_gap_m; collapse_drop_m = o%collapse_drop_m
    collapse_rotation_rad = o%collapse_rotation_rad; stop_after_collapse_s = o%stop_after_collapse_s
    rewind (unit)
    read (unit, nml=output, iostat=ios, iomsg=iomsg)
    if (.not. group_ok('output')) return
    o = output_config_t(file, every, hinge_gap_m, collapse_drop_m, collapse_rotation_rad, &
                        stop_after_collapse_s)
    close (unit)

    cfg%arch = a
    cfg%motion = m
    cfg%solver = s
    cfg%output = o
    if (any(allowed_groups == 'wall')) call read_wall_config(path, cfg%wall, status)
    if (.not. status%ok) return
    if (len_trim(cfg%arch%polygon_file) > 0) &
      cfg%arch%polygon_file = resolve_path(path, cfg%arch%polygon_file)
    if (len_trim(cfg%motion%record_file) > 0) &
      cfg%motion%record_file = resolve_path(path, cfg%motion%record_file)
    call validate_config(cfg, status)

  contains

    logical function group_ok(name)
      character(len=*), intent(in) :: name
      group_ok = .true.
      if (ios == iostat_end) then
        ios = 0   ! group absent: defaults
      else if (ios /= 0) then
        call fail(status, trim(path)//': in namelist group &'//name//': '//trim(iomsg)// &
                  '. The variables of &'//name//' are: '//group_variables(name))
        close (unit)
        group_ok = .false.
      end if
    end function group_ok

  end subroutine read_config

  !> The variables of a group with their types and units, for error messages.
  function group_variables(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    select case (name)
    case ('arch')
      text = 'embrace_deg (real, deg), n_voussoirs (integer), r_ext_m, thickness_m, width_m (real, m), '// &
             'density_kg_m3 (real), friction (real), contact_inset_m (real, m), '// &
             "restrained_springings ('none'|'left'|'right'|'both'), polygon_file (text), "// &
             'joint_friction(j) (real, the friction of joint j = 0..n_voussoirs), size_imperfection (real), '// &
             'imperfection_seed (integer)'
    case ('motion')
      text = "waveform ('afd'|'ramp'|'record'|'accelerogram'), frequency_hz (real), amplitude_m (real), "// &
             'n_attack, n_full, n_decay (integer), record_file (text), record_cutoff_hz, record_scale, '// &
             'ramp_rate_m_s3, rest_s, duration_s, '// &
             'table_gain, table_delay_s (real)'
    case ('solver')
      text = 'dt_s, theta, tol (real), max_iter (integer), alert_m (real, m), allow_nonconvergence, '// &
             'coarse_correction (logical)'
    case ('output')
      text = 'file (text), every (integer), hinge_gap_m, collapse_drop_m, collapse_rotation_rad, '// &
             'stop_after_collapse_s (real)'
    case default
      text = '(see the documentation)'
    end select
  end function group_variables

  !> Whether `value` of the &arch variable `name` is in its own range (the range that
  !> does not depend on other variables); the one rule for &arch and the sweep's lists.
  pure logical function arch_rule(name, value)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: value
    select case (name)
    case ('embrace_deg')
      arch_rule = value > 0.0_dp .and. value <= 180.0_dp
    case ('n_voussoirs')
      arch_rule = value >= 2.0_dp .and. value <= real(max_voussoirs, dp)
    case ('thickness_m', 'r_ext_m', 'width_m')
      arch_rule = value > 0.0_dp .and. value <= 1.0e3_dp
    case ('density_kg_m3')
      arch_rule = value > 0.0_dp .and. value <= 1.0e5_dp
    case ('friction', 'contact_inset_m')
      arch_rule = value >= 0.0_dp .and. value <= huge(1.0_dp)
    case ('size_imperfection')
      arch_rule = value >= 0.0_dp .and. value < 0.5_dp
    case default
      arch_rule = .false.
    end select
  end function arch_rule

  !> The range `arch_rule` checks, as text for messages.
  function arch_rule_text(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    select case (name)
    case ('embrace_deg')
      text = '0 < embrace_deg <= 180'
    case ('n_voussoirs')
      text = '2 <= n_voussoirs <= '//itoa(max_voussoirs)
    case ('friction', 'contact_inset_m')
      text = trim(name)//' >= 0 (finite)'
    case ('size_imperfection')
      text = '0 <= size_imperfection < 0.5'
    case ('thickness_m', 'r_ext_m', 'width_m')
      text = '0 < '//trim(name)//' <= 1000 m'
    case ('density_kg_m3')
      text = '0 < density_kg_m3 <= 1e5'
    case default
      text = trim(name)//' > 0 (finite)'
    end select
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



  !> Every setting of `cfg`, defaults included, in group order.
  function config_entries(cfg) result(e)
    type(config_t), intent(in) :: cfg
    type(config_entry_t), allocatable :: e(:)
    integer :: j
    allocate (e(0))
    associate (a => cfg%arch, m => cfg%motion, s => cfg%solver, o => cfg%output)
      call r('arch', 'embrace_deg', a%embrace_deg)
      call i('arch', 'n_voussoirs', a%n_voussoirs)
      call r('arch', 'r_ext_m', a%r_ext_m)
      call r('arch', 'thickness_m', a%thickness_m)
      call r('arch', 'width_m', a%width_m)
      call r('arch', 'density_kg_m3', a%density_kg_m3)
      call r('arch', 'friction', a%friction)
      call r('arch', 'contact_inset_m', a%contact_inset_m)
      call t('arch', 'restrained_springings', a%restrained_springings)
      call t('arch', 'polygon_file', a%polygon_file)
      do j = 0, max_joint
        if (a%joint_friction(j) /= unset_friction) call r('arch', 'joint_friction('//itoa(j)//')', a%joint_friction(j))
      end do
      call r('arch', 'size_imperfection', a%size_imperfection)
      call i('arch', 'imperfection_seed', a%imperfection_seed)
      call t('motion', 'waveform', m%waveform)
      call r('motion', 'frequency_hz', m%frequency_hz)
      call r('motion', 'amplitude_m', m%amplitude_m)
      call i('motion', 'n_attack', m%n_attack)
      call i('motion', 'n_full', m%n_full)
      call i('motion', 'n_decay', m%n_decay)
      call t('motion', 'record_file', m%record_file)
      call r('motion', 'record_cutoff_hz', m%record_cutoff_hz)
      call r('motion', 'ramp_rate_m_s3', m%ramp_rate_m_s3)
      call r('motion', 'rest_s', m%rest_s)
      call r('motion', 'duration_s', m%duration_s)
      call r('motion', 'table_gain', m%table_gain)
      call r('motion', 'table_delay_s', m%table_delay_s)
      call r('motion', 'record_scale', m%record_scale)
      call r('solver', 'dt_s', s%dt_s)
      call r('solver', 'theta', s%theta)
      call r('solver', 'tol', s%tol)
      call i('solver', 'max_iter', s%max_iter)
      call r('solver', 'alert_m', s%alert_m)
      call l('solver', 'allow_nonconvergence', s%allow_nonconvergence)
      call l('solver', 'coarse_correction', s%coarse_correction)
      call t('output', 'file', o%file)
      call i('output', 'every', o%every)
      call r('output', 'hinge_gap_m', o%hinge_gap_m)
      call r('output', 'collapse_drop_m', o%collapse_drop_m)
      call r('output', 'collapse_rotation_rad', o%collapse_rotation_rad)
      call r('output', 'stop_after_collapse_s', o%stop_after_collapse_s)
      if (cfg%wall%courses > 0) then
        call i('wall', 'courses', cfg%wall%courses)
        call i('wall', 'blocks_per_course', cfg%wall%blocks_per_course)
        call r('wall', 'block_width_m', cfg%wall%block_width_m)
        call r('wall', 'block_height_m', cfg%wall%block_height_m)
        call t('wall', 'bond', cfg%wall%bond)
      end if
    end associate
  contains
    subroutine r(g, n, x)
      character(len=*), intent(in) :: g, n
      real(dp), intent(in) :: x
      character(len=32) :: buf
      write (buf, '(es24.16)') x
      e = [e, config_entry_t(g, n, 'r', adjustl(buf))]
    end subroutine r
    subroutine i(g, n, x)
      character(len=*), intent(in) :: g, n
      integer, intent(in) :: x
      character(len=32) :: buf
      write (buf, '(i0)') x
      e = [e, config_entry_t(g, n, 'i', buf)]
    end subroutine i
    subroutine l(g, n, x)
      character(len=*), intent(in) :: g, n
      logical, intent(in) :: x
      e = [e, config_entry_t(g, n, 'l', merge('.true. ', '.false.', x))]
    end subroutine l
    subroutine t(g, n, x)
      character(len=*), intent(in) :: g, n, x
      e = [e, config_entry_t(g, n, 's', x)]
    end subroutine t
  end function config_entries

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
