!> The checks of every &arch, &motion, &solver and &output value (voussoir_config's
!> validate_config), apart from the reading.
submodule (voussoir_config) voussoir_config_validate
  use voussoir_kinds, only: pi
  use voussoir_text, only: fmt_significant
  implicit none

contains

  !> Check every value of `cfg` against its physical range.
  module subroutine validate_config(cfg, status)
    type(config_t), intent(inout) :: cfg
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: f
    type(config_entry_t), allocatable :: entries(:)
    logical :: exists
    integer :: j

    f = trim(cfg%source_file)
    ! No real of any group may be infinite or NaN (each would run one step, or poison
    ! the solve, and print an answer).
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
    ! Each check records the first failure only, so the user sees the first bad value.
    associate (a => cfg%arch, m => cfg%motion, s => cfg%solver, o => cfg%output)
      a%restrained_springings = lower(a%restrained_springings)
      m%waveform = lower(m%waveform)
      if (cfg%wall%courses > 0 .and. len_trim(a%polygon_file) > 0) then
        call fail(status, f//": &wall and &arch polygon_file both describe the assembly: give one of them")
        return
      end if
      if (cfg%wall%courses > 0) then
        continue   ! the wall's own group was checked when read; &arch gives its material
      else if (len_trim(a%polygon_file) == 0) then
        call need_rule('embrace_deg', a%embrace_deg)
        call need_int(arch_rule('n_voussoirs', real(a%n_voussoirs, dp)), 'arch', 'n_voussoirs', a%n_voussoirs, &
                      arch_rule_text('n_voussoirs'))
        call need_rule('r_ext_m', a%r_ext_m)
        call need(a%thickness_m > 0.0_dp .and. a%thickness_m < a%r_ext_m, &
          'arch', 'thickness_m', a%thickness_m, '0 < thickness_m < r_ext_m = '//fmt_real(a%r_ext_m))
        if (.not. status%ok) return
        call check_voussoir_length()
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

    !> Each voussoir is at least thickness_m/100 long at the intrados: a block a hundred
    !> times deeper than long is a sliver, not a voussoir, and the kernel's answer for
    !> slivers is wrong (a flat arch of slivers "collapses" under its own weight).
    subroutine check_voussoir_length()
      real(dp), parameter :: max_depth_over_length = 100.0_dp
      real(dp) :: r_int_m, length_m, min_embrace_deg
      integer :: max_n
      associate (a => cfg%arch)
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
      end associate
    end subroutine check_voussoir_length

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
