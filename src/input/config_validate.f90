!> The checks of every &arch, &motion, &solver and &output value (voussoir_config's
!> validate_config), apart from the reading.
submodule (voussoir_config) voussoir_config_validate
  use voussoir_kinds, only: pi, g_m_s2
  use voussoir_text, only: fmt_significant
  use voussoir_input_range, only: need
  implicit none

  !> The largest table acceleration of any motion, in g: not physics but a bound on
  !> typos. Shake tables and recorded earthquakes stay below a few g, and the sweeps'
  !> searches stop far below (amp_max_m = 0.5 m is 1000 g only at 22 Hz); 1e300 m ended
  !> in "NaN in the contact solve at step 1".
  real(dp), parameter :: max_table_accel_g = 1000.0_dp
  real(dp), parameter :: min_ring_ratio = 1000.0_dp  !! r_ext_m / thickness_m at most

contains

  !> Check every value of `cfg` against its physical range: the ranges of the tables
  !> (config_groups) that hold in this case, and those that depend on other variables.
  module subroutine validate_config(cfg, status)
    type(config_t), intent(inout), target :: cfg
    type(status_t), intent(inout) :: status
    type(nml_group_t) :: groups(4)
    character(len=:), allocatable :: f

    f = trim(cfg%source_file)
    cfg%warnings = ''
    call check_finite(cfg, f, status)
    if (.not. status%ok) return
    cfg%arch%restrained_springings = lower(cfg%arch%restrained_springings)
    cfg%motion%waveform = lower(cfg%motion%waveform)
    call config_groups(cfg, groups)
    ! Each check records the first failure only, so the user sees the first bad value.
    call validate_arch(cfg, groups(1), f, status)
    if (.not. status%ok) return
    call validate_motion(cfg%motion, groups(2), f, status)
    call groups(3)%check(f, status)
    ! The rest window is the arch's own capacity: never checked under loads (as the sweep).
    if (cfg%solver%rest_capacity_m_s2 > 0.0_dp .and. has_loads(cfg)) &
      call need(.false., f, 'solver', 'rest_capacity_m_s2', cfg%solver%rest_capacity_m_s2, &
                '0 with &load (the steps at rest are skipped on the arch alone)', status)
    ! The sinusoid must be resolved: at least 20 steps per period (as the sweep asks).
    associate (m => cfg%motion, s => cfg%solver)
      if (m%waveform == waveform_afd .and. s%dt_s > 0.0_dp) &
        call need(m%frequency_hz <= 1.0_dp/(20.0_dp*s%dt_s), f, 'motion', 'frequency_hz', m%frequency_hz, &
                  '0 < frequency_hz <= 1/(20 dt_s) = '//fmt_real(1.0_dp/(20.0_dp*s%dt_s)), status)
      if (m%waveform == waveform_afd) &
        call need(m%amplitude_m*m%table_gain*(2.0_dp*pi*m%frequency_hz)**2 <= max_table_accel_g*g_m_s2, &
                  f, 'motion', 'amplitude_m', m%amplitude_m, '0 <= amplitude_m <= 1000 g/(table_gain (2 pi '// &
                  'frequency_hz)^2) = '//fmt_significant(max_table_accel_g*g_m_s2/(m%table_gain* &
                  (2.0_dp*pi*m%frequency_hz)**2), 4)//' m (a full-cycle table acceleration A (2 pi f)^2 of at '// &
                  'most 1000 g)', status)
    end associate
    call check_plausible_motion(cfg, f, status)   ! within the bounds above, against the assembly
    if (.not. status%ok) return
    call check_output_file(cfg%output%file, f, status)
    call groups(4)%check(f, status)
  end subroutine validate_config

  !> No real of any group may be infinite or NaN (each would run one step, or poison
  !> the solve, and print an answer).
  subroutine check_finite(cfg, f, status)
    type(config_t), intent(in) :: cfg
    character(len=*), intent(in) :: f
    type(status_t), intent(inout) :: status
    type(config_entry_t), allocatable :: entries(:)
    integer :: j
    allocate (entries(0))   ! (gfortran warns of an unset descriptor otherwise)
    entries = config_entries(cfg)
    do j = 1, size(entries)
      if (entries(j)%kind /= 'r') cycle
      if (index(lower(entries(j)%value), 'inf') > 0 .or. index(lower(entries(j)%value), 'nan') > 0) then
        call fail(status, f//': &'//trim(entries(j)%group)//' '//trim(entries(j)%name)//' = '// &
                  trim(entries(j)%value)//' is not a finite number')
        return
      end if
    end do
  end subroutine check_finite

  !> &arch: the arch's shape (or the polygon file, or the wall's), the material, the
  !> joints' friction, the imperfection and the contact inset.
  subroutine validate_arch(cfg, g, f, status)
    type(config_t), intent(inout) :: cfg
    type(nml_group_t), intent(in) :: g
    character(len=*), intent(in) :: f
    type(status_t), intent(inout) :: status
    logical :: exists
    integer :: j
    character(len=:), allocatable :: joint

    associate (a => cfg%arch)
      if (cfg%wall%courses > 0 .and. len_trim(a%polygon_file) > 0) then
        call fail(status, f//": &wall and &arch polygon_file both describe the assembly: give one of them")
        return
      end if
      if (cfg%bridge%n_spans > 0 .and. cfg%wall%courses > 0) then
        call fail(status, f//": &wall and &bridge both describe the assembly: give one of them")
        return
      end if
      if (cfg%bridge%n_spans > 0) then
        ! &bridge was checked when read; its ring stands in the &arch values drivers read.
        call check_plausible_arch(cfg, f, status)
      else if (cfg%wall%courses > 0) then
        call check_plausible_arch(cfg, f, status)   ! the wall's own group was checked when read
      else if (len_trim(a%polygon_file) == 0) then
        call g%check(f, status, when=arch_builder)
        call need(a%thickness_m > 0.0_dp .and. a%thickness_m < a%r_ext_m, &
          f, 'arch', 'thickness_m', a%thickness_m, '0 < thickness_m < r_ext_m = '//fmt_real(a%r_ext_m), status)
        ! Before the ring's proportions: r_ext_m = 508 (millimetres) is a slip of units.
        call check_plausible_arch(cfg, f, status)
        ! A ring thinner than a thousandth of its radius is no masonry arch (the thinnest
        ! that stand are some hundredths of it), and its voussoirs are slivers whose area
        ! the geometry cannot resolve (1e-9 m ended in "zero or negative area").
        call need(a%thickness_m >= a%r_ext_m/min_ring_ratio, f, 'arch', 'thickness_m', a%thickness_m, &
          'r_ext_m/1000 = '//fmt_significant(a%r_ext_m/min_ring_ratio, 4)//' m <= thickness_m < r_ext_m = '// &
          fmt_real(a%r_ext_m)//' (a ring at least a thousandth of its radius thick)', status)
        if (.not. status%ok) return
        call check_voussoir_length(a, f, status)
        if (.not. status%ok) return
      else
        inquire (file=a%polygon_file, exist=exists)
        if (.not. exists) then
          call fail(status, f//": &arch polygon_file = '"//trim(a%polygon_file)//"': no such file")
          return
        end if
        call g%check(f, status, when=polygon_assembly)
        call check_plausible_arch(cfg, f, status)
      end if
      call g%check(f, status)
      do j = 0, max_joint
        if (a%joint_friction(j) == unset_friction) cycle
        joint = 'joint_friction('//itoa(j)//')'
        if (len_trim(a%polygon_file) > 0) then
          call need(.false., f, 'arch', joint, a%joint_friction(j), &
                    'none: a polygon_file assembly has no numbered joints', status)
        else
          call need(j <= a%n_voussoirs, f, 'arch', joint, a%joint_friction(j), &
                    'none: the joints are 0..n_voussoirs = '//itoa(a%n_voussoirs), status)
        end if
      end do
      if (a%size_imperfection > 0.0_dp .and. len_trim(a%polygon_file) > 0) &
        call need(.false., f, 'arch', 'size_imperfection', a%size_imperfection, &
                  '0: a polygon_file assembly has no voussoirs', status)
      ! A bracket stands off its voussoir by less than the ring's thickness, and only where
      ! there is one.
      if (a%bracket_gap_m > 0.0_dp .and. len_trim(a%polygon_file) == 0) then
        call need(a%restrained_springings /= springings_none, f, 'arch', 'bracket_gap_m', a%bracket_gap_m, &
                  "0 with restrained_springings = 'none' (there is no bracket to stand off)", status)
        call need(a%bracket_gap_m < a%thickness_m, f, 'arch', 'bracket_gap_m', a%bracket_gap_m, &
                  '0 <= bracket_gap_m < thickness_m = '//fmt_real(a%thickness_m), status)
      end if
      call need(a%contact_inset_m >= 0.0_dp .and. a%contact_inset_m < 0.5_dp*a%thickness_m, &
                f, 'arch', 'contact_inset_m', a%contact_inset_m, &
                '0 <= contact_inset_m < thickness_m/2 = '//fmt_real(0.5_dp*a%thickness_m), status)
    end associate
  end subroutine validate_arch

  !> &motion: the waveform's own variables (the one `select case` on the waveforms
  !> here), and what every waveform has.
  subroutine validate_motion(m, g, f, status)
    type(motion_config_t), intent(in) :: m
    type(nml_group_t), intent(in) :: g
    character(len=*), intent(in) :: f
    type(status_t), intent(inout) :: status

    call g%check(f, status)
    if (.not. status%ok) return
    select case (m%waveform)
    case (waveform_ramp)
      call need(m%duration_s > 0.0_dp, f, 'motion', 'duration_s', m%duration_s, &
                'duration_s > 0 (the ramp has no end)', status)
    case (waveform_record)
      call need_file(m%record_file, f, status)
    case (waveform_accelerogram)
      if (len_trim(m%record_file) == 0) then
        call fail(status, f//": &motion record_file is empty: waveform = 'accelerogram' needs a PEER .AT2 "// &
                  'file or a CSV with columns t_s, accel_m_s2')
        return
      end if
      call need_file(m%record_file, f, status)
    end select
    call g%check(f, status, when=m%waveform)
    call validate_vertical_and_polarity(m, f, status)
  end subroutine validate_motion

  !> The vertical component (a ratio for afd and accelerograms, or an own record for an
  !> accelerogram, not both) and the polarity (1 or -1, accelerograms only).
  subroutine validate_vertical_and_polarity(m, f, status)
    type(motion_config_t), intent(in) :: m
    character(len=*), intent(in) :: f
    type(status_t), intent(inout) :: status
    logical :: exists
    if (.not. status%ok) return
    call need(m%record_polarity == 1 .or. m%record_polarity == -1, f, 'motion', 'record_polarity', &
              m%record_polarity, 'record_polarity = 1 or -1 (-1: the horizontal record played with its sign reversed)', &
              status)
    if (m%record_polarity == -1 .and. m%waveform /= waveform_accelerogram) &
      call need(.false., f, 'motion', 'record_polarity', m%record_polarity, &
                "1: waveform = '"//trim(m%waveform)//"' has no record to reverse (only 'accelerogram')", status)
    if (m%vertical_ratio /= 0.0_dp .and. m%waveform /= waveform_afd .and. m%waveform /= waveform_accelerogram) &
      call need(.false., f, 'motion', 'vertical_ratio', m%vertical_ratio, &
                "0: waveform = '"//trim(m%waveform)//"' has no vertical component (only 'afd' and 'accelerogram')", &
                status)
    if (.not. status%ok .or. len_trim(m%record_vertical_file) == 0) return
    if (m%waveform /= waveform_accelerogram) then
      call fail(status, f//": &motion record_vertical_file is set but waveform = '"//trim(m%waveform)// &
                "': only an 'accelerogram' has a vertical record")
    else if (m%vertical_ratio /= 0.0_dp) then
      call fail(status, f//': &motion record_vertical_file and vertical_ratio both give the vertical component: '// &
                'set one of them')
    else
      inquire (file=m%record_vertical_file, exist=exists)
      if (.not. exists) call fail(status, f//": &motion record_vertical_file = '"// &
                                  trim(m%record_vertical_file)//"': no such file")
    end if
  end subroutine validate_vertical_and_polarity

  !> The record named by &motion record_file exists.
  subroutine need_file(record_file, f, status)
    character(len=*), intent(in) :: record_file, f
    type(status_t), intent(inout) :: status
    logical :: exists
    if (.not. status%ok) return
    inquire (file=record_file, exist=exists)
    if (.not. exists) call fail(status, f//": &motion record_file = '"//trim(record_file)//"': no such file")
  end subroutine need_file

  !> Each voussoir is at least thickness_m/100 long at the intrados: a block a hundred
  !> times deeper than long is a sliver, not a voussoir, and the kernel's answer for
  !> slivers is wrong (a flat arch of slivers "collapses" under its own weight).
  subroutine check_voussoir_length(a, f, status)
    type(arch_config_t), intent(in) :: a
    character(len=*), intent(in) :: f
    type(status_t), intent(inout) :: status
    real(dp), parameter :: max_depth_over_length = 100.0_dp
    real(dp) :: r_int_m, length_m, min_embrace_deg
    integer :: max_n
    r_int_m = a%r_ext_m - a%thickness_m
    length_m = r_int_m*a%embrace_deg*pi/180.0_dp/a%n_voussoirs
    if (length_m >= a%thickness_m/max_depth_over_length) return
    min_embrace_deg = a%n_voussoirs*a%thickness_m/(max_depth_over_length*r_int_m)*180.0_dp/pi
    ! Rounded up to 3 digits, so that the bound printed passes.
    min_embrace_deg = 0.01_dp*ceiling(100.0_dp*min_embrace_deg)
    if (min_embrace_deg <= 180.0_dp) then
      call fail(status, f//': &arch embrace_deg = '//fmt_real(a%embrace_deg)// &
                ' is outside the allowed range '//fmt_significant(min_embrace_deg, 6)//' <= embrace_deg <= 180'// &
                ' for n_voussoirs = '//itoa(a%n_voussoirs)//', thickness_m = '//fmt_real(a%thickness_m)// &
                ', r_ext_m = '//fmt_real(a%r_ext_m)//': each voussoir must be at least thickness_m/100'// &
                ' long at the intrados (these would be '//fmt_significant(length_m, 4)//' m)')
    else
      max_n = floor(r_int_m*a%embrace_deg*pi/180.0_dp*max_depth_over_length/a%thickness_m)
      call fail(status, f//': &arch n_voussoirs = '//itoa(a%n_voussoirs)// &
                ' is outside the allowed range 2 <= n_voussoirs <= '//itoa(max_n)// &
                ' for embrace_deg = '//fmt_real(a%embrace_deg)//', thickness_m = '//fmt_real(a%thickness_m)// &
                ', r_ext_m = '//fmt_real(a%r_ext_m)//': each voussoir must be at least thickness_m/100'// &
                ' long at the intrados (these would be '//fmt_significant(length_m, 4)//' m)')
    end if
  end subroutine check_voussoir_length

  !> The result file can be written where it is named: its folder exists, it is not a
  !> folder itself, and it is not the input (checked before any simulation).
  subroutine check_output_file(file, f, status)
    character(len=*), intent(in) :: file, f
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: out, folder
    integer :: k
    logical :: exists
    if (len_trim(file) == 0) then
      call fail(status, f//': &output file is empty')
      return
    end if
    out = trim(file)
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

end submodule voussoir_config_validate
