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
    character(len=path_len) :: source_file = ''
  end type config_t

  !> One effective setting: group, name, type ('r', 'i', 'l', 's') and value as text.
  type :: config_entry_t
    character(len=16) :: group = ''
    character(len=32) :: name = ''
    character(len=1) :: kind = 's'
    character(len=path_len) :: value = ''
  end type config_entry_t

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
    logical :: allow_nonconvergence
    namelist /arch/ embrace_deg, n_voussoirs, r_ext_m, thickness_m, width_m, density_kg_m3, &
      friction, contact_inset_m, restrained_springings, polygon_file, joint_friction, size_imperfection, &
      imperfection_seed
    namelist /motion/ waveform, frequency_hz, amplitude_m, n_attack, n_full, n_decay, &
      record_file, record_cutoff_hz, ramp_rate_m_s3, rest_s, duration_s, table_gain, table_delay_s, &
      record_scale
    namelist /solver/ dt_s, theta, tol, max_iter, alert_m, allow_nonconvergence
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
      'allow_nonconvergence'], status)
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
    allow_nonconvergence = s%allow_nonconvergence
    rewind (unit)
    read (unit, nml=solver, iostat=ios, iomsg=iomsg)
    if (.not. group_ok('solver')) return
    s = solver_config_t(dt_s, theta, tol, max_iter, alert_m, allow_nonconvergence)

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
      text = 'dt_s, theta, tol (real), max_iter (integer), alert_m (real, m), allow_nonconvergence (logical)'
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

  !> A path without leading './' (to compare two names of one file given alike).
  pure function plain_path(path) result(p)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: p
    p = trim(adjustl(path))
    do while (len(p) > 2)
      if (p(1:2) /= './') exit
      p = p(3:)
    end do
  end function plain_path

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

  !> Check every value of `cfg` against its physical range.
  subroutine validate_config(cfg, status)
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: f
    logical :: exists
    integer :: j

    f = trim(cfg%source_file)
    ! No real of any group may be infinite or NaN (each would run one step, or poison
    ! the solve, and print an answer).
    block
      type(config_entry_t), allocatable :: e(:)
      e = config_entries(cfg)
      do j = 1, size(e)
        if (e(j)%kind /= 'r') cycle
        if (index(lower(e(j)%value), 'inf') > 0 .or. index(lower(e(j)%value), 'nan') > 0) then
          call fail(status, f//': &'//trim(e(j)%group)//' '//trim(e(j)%name)//' = '//trim(e(j)%value)// &
                    ' is not a finite number')
          return
        end if
      end do
    end block
    ! Each check records the first failure only, so the user sees the first bad value.
    associate (a => cfg%arch, m => cfg%motion, s => cfg%solver, o => cfg%output)
      a%restrained_springings = lower(a%restrained_springings)
      m%waveform = lower(m%waveform)
      if (len_trim(a%polygon_file) == 0) then
        call need_rule('embrace_deg', a%embrace_deg)
        call need_int(arch_rule('n_voussoirs', real(a%n_voussoirs, dp)), 'arch', 'n_voussoirs', a%n_voussoirs, &
                      arch_rule_text('n_voussoirs'))
        call need_rule('r_ext_m', a%r_ext_m)
        call need(a%thickness_m > 0.0_dp .and. a%thickness_m < a%r_ext_m, &
          'arch', 'thickness_m', a%thickness_m, '0 < thickness_m < r_ext_m = '//fmt_real(a%r_ext_m))
        if (.not. status%ok) return
        select case (a%restrained_springings)
        case ('none', 'left', 'right', 'both')
        case default
          call fail(status, f//": &arch restrained_springings = '"//trim(a%restrained_springings)// &
                    "' is not one of 'none', 'left', 'right', 'both'")
          return
        end select
      else
        inquire (file=a%polygon_file, exist=exists)
        if (.not. exists) then
          call fail(status, f//": &arch polygon_file = '"//trim(a%polygon_file)//"': no such file")
          return
        end if
        call need_rule('thickness_m', a%thickness_m)
      end if
      call need_rule('width_m', a%width_m)
      call need_rule('density_kg_m3', a%density_kg_m3)
      call need_rule('friction', a%friction)
      do j = 0, max_joint
        if (a%joint_friction(j) == unset_friction) cycle
        call need(a%joint_friction(j) >= 0.0_dp .and. a%joint_friction(j) <= huge(1.0_dp), &
                  'arch', 'joint_friction('//itoa(j)//')', a%joint_friction(j), 'joint_friction >= 0')
        if (len_trim(a%polygon_file) > 0) then
          call need(.false., 'arch', 'joint_friction('//itoa(j)//')', a%joint_friction(j), &
                    'none: a polygon_file assembly has no numbered joints')
        else
          call need(j <= a%n_voussoirs, 'arch', 'joint_friction('//itoa(j)//')', a%joint_friction(j), &
                    'none: the joints are 0..n_voussoirs = '//itoa(a%n_voussoirs))
        end if
      end do
      call need(a%size_imperfection >= 0.0_dp .and. a%size_imperfection < 0.5_dp, 'arch', 'size_imperfection', &
                a%size_imperfection, '0 <= size_imperfection < 0.5')
      call need_int(a%imperfection_seed >= 0, 'arch', 'imperfection_seed', a%imperfection_seed, 'imperfection_seed >= 0')
      if (a%size_imperfection > 0.0_dp .and. len_trim(a%polygon_file) > 0) &
        call need(.false., 'arch', 'size_imperfection', a%size_imperfection, '0: a polygon_file assembly has no voussoirs')
      call need(a%contact_inset_m >= 0.0_dp .and. a%contact_inset_m < 0.5_dp*a%thickness_m, &
          'arch', 'contact_inset_m', a%contact_inset_m, &
                   '0 <= contact_inset_m < thickness_m/2 = '//fmt_real(0.5_dp*a%thickness_m))

      if (.not. status%ok) return
      select case (m%waveform)
      case ('afd')
        call need(m%frequency_hz > 0.0_dp, 'motion', 'frequency_hz', m%frequency_hz, 'frequency_hz > 0')
        call need(m%amplitude_m >= 0.0_dp, 'motion', 'amplitude_m', m%amplitude_m, 'amplitude_m >= 0')
        call need_int(m%n_attack >= 1, 'motion', 'n_attack', m%n_attack, 'n_attack >= 1')
        call need_int(m%n_full >= 0, 'motion', 'n_full', m%n_full, 'n_full >= 0')
        call need_int(m%n_decay >= 1, 'motion', 'n_decay', m%n_decay, 'n_decay >= 1')
        call need(m%table_gain > 0.0_dp, 'motion', 'table_gain', m%table_gain, 'table_gain > 0')
        call need(m%table_delay_s >= 0.0_dp, 'motion', 'table_delay_s', m%table_delay_s, 'table_delay_s >= 0')
      case ('ramp')
        call need(m%ramp_rate_m_s3 /= 0.0_dp, &
          'motion', 'ramp_rate_m_s3', m%ramp_rate_m_s3, 'ramp_rate_m_s3 /= 0')
        call need(m%duration_s > 0.0_dp, &
          'motion', 'duration_s', m%duration_s, 'duration_s > 0 (the ramp has no end)')
      case ('record')
        inquire (file=m%record_file, exist=exists)
        if (.not. exists) then
          call fail(status, f//": &motion record_file = '"//trim(m%record_file)//"': no such file")
          return
        end if
        call need(m%record_cutoff_hz >= 0.0_dp, &
          'motion', 'record_cutoff_hz', m%record_cutoff_hz, 'record_cutoff_hz >= 0 (0: no filter)')
      case ('accelerogram')
        if (len_trim(m%record_file) == 0) then
          call fail(status, f//": &motion record_file is empty: waveform = 'accelerogram' needs a PEER .AT2 "// &
                    'file or a CSV with columns t_s, accel_m_s2')
          return
        end if
        inquire (file=m%record_file, exist=exists)
        if (.not. exists) then
          call fail(status, f//": &motion record_file = '"//trim(m%record_file)//"': no such file")
          return
        end if
        call need(m%record_scale > 0.0_dp .and. m%record_scale <= huge(1.0_dp), &
          'motion', 'record_scale', m%record_scale, 'record_scale > 0 (finite)')
      case default
        call fail(status, f//": &motion waveform = '"//trim(m%waveform)// &
                  "' is not one of 'afd', 'ramp', 'record', 'accelerogram'")
        return
      end select
      call need(m%rest_s >= 0.0_dp, 'motion', 'rest_s', m%rest_s, 'rest_s >= 0')
      call need(m%duration_s >= 0.0_dp, 'motion', 'duration_s', m%duration_s, 'duration_s >= 0')

      call need(s%dt_s > 0.0_dp .and. s%dt_s <= 0.1_dp, 'solver', 'dt_s', s%dt_s, '0 < dt_s <= 0.1')
      call need(s%theta >= 0.5_dp .and. s%theta <= 1.0_dp, 'solver', 'theta', s%theta, '0.5 <= theta <= 1')
      call need(s%tol > 0.0_dp .and. s%tol < 1.0_dp, 'solver', 'tol', s%tol, '0 < tol < 1')
      call need_int(s%max_iter >= 1, 'solver', 'max_iter', s%max_iter, 'max_iter >= 1')
      ! The sinusoid must be resolved: at least 20 steps per period (as the sweep asks).
      if (m%waveform == 'afd' .and. s%dt_s > 0.0_dp) &
        call need(m%frequency_hz <= 1.0_dp/(20.0_dp*s%dt_s), 'motion', 'frequency_hz', m%frequency_hz, &
                  '0 < frequency_hz <= 1/(20 dt_s) = '//fmt_real(1.0_dp/(20.0_dp*s%dt_s)))
      call need(s%alert_m >= 0.0_dp, 'solver', 'alert_m', s%alert_m, 'alert_m >= 0 (0: automatic)')

      if (len_trim(o%file) == 0) then
        call fail(status, f//': &output file is empty')
        return
      end if
      call check_output_file()
      if (.not. status%ok) return
      call need_int(o%every >= 1, 'output', 'every', o%every, 'every >= 1')
      call need(o%hinge_gap_m >= 0.0_dp, 'output', 'hinge_gap_m', o%hinge_gap_m, 'hinge_gap_m >= 0')
      call need(o%collapse_drop_m >= 0.0_dp, &
          'output', 'collapse_drop_m', o%collapse_drop_m, 'collapse_drop_m >= 0')
      call need(o%collapse_rotation_rad > 0.0_dp, &
          'output', 'collapse_rotation_rad', o%collapse_rotation_rad, 'collapse_rotation_rad > 0')
    end associate

  contains

    !> The result file can be written where it is named: its folder exists, it is not a
    !> folder itself, and it is not the input (checked before any simulation).
    subroutine check_output_file()
      character(len=:), allocatable :: out, folder
      integer :: k
      out = trim(cfg%output%file)
      k = index(out, '/', back=.true.)
      if (k > 1) then
        folder = out(:k - 1)
        inquire (file=folder//'/.', exist=exists)
        if (.not. exists) then
          call fail(status, f//": &output file = '"//out//"': the folder '"//folder//"' does not exist")
          return
        end if
      end if
      inquire (file=out//'/.', exist=exists)
      if (exists) then
        call fail(status, f//": &output file = '"//out//"' is a folder: name a file in it")
        return
      end if
      if (plain_path(out) == plain_path(f)) &
        call fail(status, f//": &output file = '"//out//"' is the input file itself: it would be overwritten")
    end subroutine check_output_file

    subroutine need(good, group, name, value, allowed)
      logical, intent(in) :: good
      character(len=*), intent(in) :: group, name, allowed
      real(dp), intent(in) :: value
      if (good .or. .not. status%ok) return
      call fail(status, f//': &'//group//' '//name//' = '//fmt_real(value)// &
                ' is outside the allowed range '//allowed)
    end subroutine need

    subroutine need_rule(name, value)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: value
      call need(arch_rule(name, value), 'arch', name, value, arch_rule_text(name))
    end subroutine need_rule

    subroutine need_int(good, group, name, value, allowed)
      logical, intent(in) :: good
      character(len=*), intent(in) :: group, name, allowed
      integer, intent(in) :: value
      character(len=16) :: text
      if (good .or. .not. status%ok) return
      write (text, '(i0)') value
      call fail(status, f//': &'//group//' '//name//' = '//trim(text)// &
                ' is outside the allowed range '//allowed)
    end subroutine need_int

  end subroutine validate_config


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
      call t('output', 'file', o%file)
      call i('output', 'every', o%every)
      call r('output', 'hinge_gap_m', o%hinge_gap_m)
      call r('output', 'collapse_drop_m', o%collapse_drop_m)
      call r('output', 'collapse_rotation_rad', o%collapse_rotation_rad)
      call r('output', 'stop_after_collapse_s', o%stop_after_collapse_s)
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
