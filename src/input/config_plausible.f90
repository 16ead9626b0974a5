!> Plausibility of an input against the assembly's own scale (issue 34): the slips of
!> units that pass every range but describe another structure or another motion, the
!> commonest being millimetres given as metres (`amplitude_m = 46`, `r_ext_m = 508`).
!> What no real case needs is refused with a hint ("did you mean millimetres (0.046 m)?");
!> what a real case could need is kept with a warning in cfg%warnings, which the drivers
!> print. docs/input.md, "Plausibility".
submodule (voussoir_config) voussoir_config_plausible
  use voussoir_kinds, only: pi, g_m_s2
  use voussoir_text, only: fmt_significant
  implicit none

  !> The longest masonry arches span about 150 m (the Danhe bridge, 146 m).
  real(dp), parameter :: max_span_m = 200.0_dp
  !> Their rings are some metres thick.
  real(dp), parameter :: max_ring_m = 10.0_dp
  !> An arch barrel (the out-of-plane width) of more than this is warned.
  real(dp), parameter :: warn_width_m = 100.0_dp
  !> No shaking table nor recorded earthquake reaches this table acceleration; a small
  !> block at a high frequency may need it in a simulation, so it is warned, not refused.
  real(dp), parameter :: warn_table_accel_g = 10.0_dp

contains

  !> The arch builder's ring against the sizes of real masonry arches: an arch wider
  !> than any built, a ring thicker than any built, refused; a barrel wider than 100 m,
  !> warned.
  module subroutine check_plausible_arch(cfg, f, status)
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: f
    type(status_t), intent(inout) :: status
    real(dp) :: span_m
    character(len=:), allocatable :: also

    if (.not. status%ok) return
    associate (a => cfg%arch)
      if (cfg%wall%courses > 0 .or. len_trim(a%polygon_file) > 0 .or. cfg%bridge%n_spans > 0) then
        call plausible_width(cfg, f)
        return
      end if
      span_m = arch_span_m(a%r_ext_m, a%embrace_deg)
      if (span_m > max_span_m) then
        also = ''
        if (a%thickness_m > max_ring_m) also = ', thickness_m = '//fmt_significant(a%thickness_m/1000.0_dp, 4)//' m'
        call fail(status, f//': &arch r_ext_m = '//fmt_real(a%r_ext_m)//' m and embrace_deg = '// &
                  fmt_real(a%embrace_deg)//' make an arch '//fmt_significant(span_m, 4)//' m wide, wider than any '// &
                  'masonry arch (the longest span about 150 m; allowed: a span of at most '//fmt_real(max_span_m)// &
                  ' m)'//millimetres_hint('r_ext_m', a%r_ext_m, span_m/1000.0_dp <= max_span_m, also))
        return
      end if
      if (a%thickness_m > max_ring_m) then
        call fail(status, f//': &arch thickness_m = '//fmt_real(a%thickness_m)//' m is thicker than any masonry '// &
                  'arch ring (allowed: at most '//fmt_real(max_ring_m)//' m)'// &
                  millimetres_hint('thickness_m', a%thickness_m, .true., ''))
        return
      end if
    end associate
    call plausible_width(cfg, f)
  end subroutine check_plausible_arch

  !> A barrel or wall more than 100 m wide out of its plane: warned (the forces scale
  !> with it, the accelerations do not, so a real long vault may give it).
  subroutine plausible_width(cfg, f)
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: f
    if (cfg%arch%width_m > warn_width_m) &
      call warn(cfg, f//': &arch width_m = '//fmt_real(cfg%arch%width_m)//' m is the out-of-plane width of the '// &
                'blocks (more than '//fmt_real(warn_width_m)//' m)'// &
                millimetres_hint('width_m', cfg%arch%width_m, .true., ''))
  end subroutine plausible_width

  !> The afd motion against the assembly: an amplitude larger than the assembly's span
  !> refused; a commanded table acceleration A (2 pi f)^2 beyond 10 g warned.
  module subroutine check_plausible_motion(cfg, f, status)
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: f
    type(status_t), intent(inout) :: status
    real(dp) :: span_m, accel_g
    character(len=:), allocatable :: what

    if (.not. status%ok) return
    associate (m => cfg%motion)
      if (m%waveform /= waveform_afd .or. m%amplitude_m <= 0.0_dp) return
      call assembly_span(cfg, span_m, what)
      if (span_m > 0.0_dp .and. m%amplitude_m > span_m) then
        call fail(status, f//': &motion amplitude_m = '//fmt_real(m%amplitude_m)//' m is larger than '//what// &
                  ' ('//fmt_significant(span_m, 3)//' m; allowed: amplitude_m <= '//fmt_significant(span_m, 3)// &
                  ' m)'//millimetres_hint('amplitude_m', m%amplitude_m, &
                  m%amplitude_m >= 1.0_dp .and. m%amplitude_m/1000.0_dp <= span_m, ''))
        return
      end if
      accel_g = m%amplitude_m*m%table_gain*(2.0_dp*pi*m%frequency_hz)**2/g_m_s2
      if (accel_g > warn_table_accel_g) &
        call warn(cfg, f//': &motion amplitude_m = '//fmt_real(m%amplitude_m)//' m at frequency_hz = '// &
                  fmt_real(m%frequency_hz)//' commands a full-cycle table acceleration A (2 pi f)^2 of '// &
                  fmt_significant(accel_g, 3)//' g, beyond any shaking table or earthquake ('// &
                  fmt_real(warn_table_accel_g)//' g): check that amplitude_m is in metres and frequency_hz in '// &
                  'hertz (not radians per second)')
    end associate
  end subroutine check_plausible_motion

  !> The horizontal extent of the assembly that the config builds [m] and its name in
  !> messages; 0 for a polygon file (its blocks are read later, by the assembly).
  module subroutine assembly_span(cfg, span_m, what)
    type(config_t), intent(in) :: cfg
    real(dp), intent(out) :: span_m
    character(len=:), allocatable, intent(out) :: what
    span_m = 0.0_dp
    what = ''
    if (cfg%bridge%n_spans > 0) then
      span_m = bridge_length_m(cfg%bridge)
      what = "the bridge's length"
    else if (cfg%wall%courses > 0) then
      span_m = cfg%wall%blocks_per_course*cfg%wall%block_width_m
      what = "the wall's length"
    else if (len_trim(cfg%arch%polygon_file) == 0) then
      span_m = arch_span_m(cfg%arch%r_ext_m, cfg%arch%embrace_deg)
      what = "the arch's span"
    end if
  end subroutine assembly_span

  !> The chord between the extrados ends of an arch of embrace at most 180 degrees [m].
  pure real(dp) function arch_span_m(r_ext_m, embrace_deg)
    real(dp), intent(in) :: r_ext_m, embrace_deg
    arch_span_m = 2.0_dp*r_ext_m*sin(0.5_dp*min(embrace_deg, 180.0_dp)*pi/180.0_dp)
  end function arch_span_m

  !> ': did you mean millimetres (name = value/1000 m)?' when that would pass (and the
  !> value reads as millimetres: an amplitude of at least 1).
  function millimetres_hint(name, value, passes, also) result(text)
    character(len=*), intent(in) :: name, also
    real(dp), intent(in) :: value
    logical, intent(in) :: passes
    character(len=:), allocatable :: text
    text = ''
    if (passes) text = ': did you mean millimetres ('//name//' = '//fmt_significant(value/1000.0_dp, 4)//' m'// &
                       also//')?'
  end function millimetres_hint

  !> Add one warning line to cfg%warnings.
  subroutine warn(cfg, text)
    type(config_t), intent(inout) :: cfg
    character(len=*), intent(in) :: text
    if (len_trim(cfg%warnings) > 0) then
      cfg%warnings = trim(cfg%warnings)//new_line('a')//text
    else
      cfg%warnings = text
    end if
  end subroutine warn

end submodule voussoir_config_plausible
