!> Base motion of the shaking table.
!>
!> Every motion starts at `start_s` (&motion lead_s), the table still before it.
!>
!> `afd`: the commanded sinusoid with attack, full and decay envelopes of
!> docs/measured_data.md, velocity and acceleration its exact derivatives.
!> `record`: a measured table displacement record, low-pass filtered (zero-phase
!> Butterworth), velocity and acceleration by central differences of the filtered record.
!> `ramp`: no table motion; an inertial horizontal load whose acceleration grows at a
!> constant rate (the quasi-static capacity test, in the frame of the table).
!> `accelerogram`: a ground-motion record drives the table by its acceleration, linear
!> between samples; velocity and displacement are its exact
!> integrals (piecewise quadratic and cubic), and after the last sample the table keeps
!> its final velocity (the exact integral of a zero acceleration).
!>
!> The vertical component (`motion_eval_vertical`, upwards positive): none by default;
!> for afd and accelerograms a ratio times the horizontal (`motion_set_vertical_ratio`),
!> or for accelerograms an own record on the horizontal's time steps
!> (`motion_set_vertical_record`), integrated exactly as the horizontal is.
module voussoir_motion
  use voussoir_kinds, only: dp, pi
  use voussoir_status, only: status_t, fail
  use voussoir_numeric_csv, only: read_csv_columns
  use voussoir_ground_record, only: record_intensity_t, record_intensity, integrate_linear_accel
  implicit none
  private

  public :: motion_t, motion_afd, motion_ramp, motion_record, motion_accelerogram, motion_eval
  public :: motion_duration_s, motion_eval_vertical, motion_set_vertical_ratio, motion_set_vertical_record
  public :: waveform_afd, waveform_ramp, waveform_record, waveform_accelerogram

  integer, parameter :: waveform_afd = 1, waveform_ramp = 2, waveform_record = 3, waveform_accelerogram = 4
  !> The kinds of vertical component.
  integer, parameter, public :: vertical_none = 0, vertical_ratio_of_afd = 1, vertical_samples = 2

  !> A table motion, ready to evaluate at any time.
  type :: motion_t
    integer :: waveform = waveform_afd
    real(dp) :: frequency_hz = 0.0_dp
    real(dp) :: amplitude_m = 0.0_dp
    real(dp) :: t_attack_s = 0.0_dp, t_full_s = 0.0_dp, t_decay_s = 0.0_dp
    real(dp) :: ramp_rate_m_s3 = 0.0_dp  !! d(load acceleration)/dt, towards +x if > 0
    real(dp) :: gain = 1.0_dp            !! actuator model: table / command amplitude
    real(dp) :: delay_s = 0.0_dp         !! actuator model: lag of the table [s]
    ! Record (filtered samples) or accelerogram (samples and their exact integrals).
    real(dp) :: dt_record_s = 0.0_dp
    real(dp), allocatable :: x_m(:), v_m_s(:), a_m_s2(:)
    real(dp) :: start_s = 0.0_dp                 !! when the motion starts, the table still before [s]
    type(record_intensity_t) :: intensity        !! accelerogram: of the acceleration as played
    character(len=512) :: record_name = ''        !! accelerogram: its file name without extension
    character(len=512) :: record_description = '' !! accelerogram: event and station, if the file says
    ! The vertical component: none, a ratio times the horizontal (afd), or samples (accelerogram).
    integer :: vertical = vertical_none
    real(dp) :: vertical_ratio = 0.0_dp          !! afd: vertical / horizontal motion
    real(dp), allocatable :: y_m(:), vy_m_s(:), ay_m_s2(:) !! accelerogram: vertical samples and integrals
  end type motion_t

contains

  !> The commanded `afd` motion, optionally played by an actuator that scales it by
  !> `gain` and lags it by `delay_s` (table(t) = gain command(t - delay)).
  pure function motion_afd(frequency_hz, amplitude_m, n_attack, n_full, n_decay, gain, delay_s) result(m)
    real(dp), intent(in) :: frequency_hz, amplitude_m
    integer, intent(in) :: n_attack, n_full, n_decay
    real(dp), intent(in), optional :: gain, delay_s
    type(motion_t) :: m
    if (present(gain)) m%gain = gain
    if (present(delay_s)) m%delay_s = delay_s
    m%waveform = waveform_afd
    m%frequency_hz = frequency_hz
    m%amplitude_m = amplitude_m
    m%t_attack_s = n_attack/frequency_hz
    m%t_full_s = n_full/frequency_hz
    m%t_decay_s = n_decay/frequency_hz
  end function motion_afd

  !> The quasi-static ramp of horizontal load acceleration.
  pure function motion_ramp(ramp_rate_m_s3) result(m)
    real(dp), intent(in) :: ramp_rate_m_s3
    type(motion_t) :: m
    m%waveform = waveform_ramp
    m%ramp_rate_m_s3 = ramp_rate_m_s3
  end function motion_ramp

  !> The table driven by the acceleration samples `accel_m_s2` (already scaled), `dt_s`
  !> apart, the first one at `start_s` (the table still before it).
  pure function motion_accelerogram(accel_m_s2, dt_s, start_s) result(m)
    real(dp), intent(in) :: accel_m_s2(:), dt_s, start_s
    type(motion_t) :: m
    m%waveform = waveform_accelerogram
    m%dt_record_s = dt_s
    m%start_s = start_s
    allocate (m%a_m_s2, source=accel_m_s2)
    allocate (m%v_m_s(size(accel_m_s2)), m%x_m(size(accel_m_s2)))
    call integrate_linear_accel(m%a_m_s2, dt_s, m%v_m_s, m%x_m)
    m%intensity = record_intensity(m%a_m_s2, dt_s)
  end function motion_accelerogram

  !> End [s] of the motion: its start and its length (the ramp, which has no end: its start).
  pure real(dp) function motion_duration_s(m)
    type(motion_t), intent(in) :: m
    select case (m%waveform)
    case (waveform_afd)
      motion_duration_s = m%t_attack_s + m%t_full_s + m%t_decay_s + m%delay_s + m%start_s
    case (waveform_record)
      motion_duration_s = (size(m%x_m) - 1)*m%dt_record_s + m%start_s
    case (waveform_accelerogram)
      motion_duration_s = m%start_s + (size(m%a_m_s2) - 1)*m%dt_record_s
    case default
      motion_duration_s = m%start_s
    end select
  end function motion_duration_s

  !> Table displacement [m], velocity [m/s] and acceleration [m/s2] at time `t_s`. For
  !> the ramp, x = v = 0 and `a` is the inertial load acceleration towards +x.
  pure subroutine motion_eval(m, t_s, x, v, a)
    type(motion_t), intent(in) :: m
    real(dp), intent(in) :: t_s
    real(dp), intent(out) :: x, v, a
    real(dp) :: e, de, d2e, w, s, c, tau, f, t
    integer :: i

    x = 0.0_dp
    v = 0.0_dp
    a = 0.0_dp
    select case (m%waveform)
    case (waveform_afd)
      t = t_s - m%start_s - m%delay_s
      if (t < 0.0_dp) return
      if (t < m%t_attack_s) then
        f = pi/m%t_attack_s
        e = sin(0.5_dp*f*t)**2
        de = 0.5_dp*f*sin(f*t)
        d2e = 0.5_dp*f*f*cos(f*t)
      else if (t < m%t_attack_s + m%t_full_s) then
        e = 1.0_dp
        de = 0.0_dp
        d2e = 0.0_dp
      else if (t < m%t_attack_s + m%t_full_s + m%t_decay_s) then
        tau = t - m%t_attack_s - m%t_full_s
        f = pi/m%t_decay_s
        e = cos(0.5_dp*f*tau)**2
        de = -0.5_dp*f*sin(f*tau)
        d2e = -0.5_dp*f*f*cos(f*tau)
      else
        return
      end if
      w = 2.0_dp*pi*m%frequency_hz
      s = sin(w*t)
      c = cos(w*t)
      x = m%gain*m%amplitude_m*e*s
      v = m%gain*m%amplitude_m*(de*s + e*w*c)
      a = m%gain*m%amplitude_m*(d2e*s + 2.0_dp*de*w*c - e*w*w*s)
    case (waveform_ramp)
      a = m%ramp_rate_m_s3*max(t_s - m%start_s, 0.0_dp)
    case (waveform_record)
      t = t_s - m%start_s
      if (t <= 0.0_dp) then
        x = m%x_m(1)
        return
      end if
      f = t/m%dt_record_s
      i = int(f) + 1
      if (i >= size(m%x_m)) then
        x = m%x_m(size(m%x_m))
        return
      end if
      f = f - (i - 1)
      x = (1.0_dp - f)*m%x_m(i) + f*m%x_m(i + 1)
      v = (1.0_dp - f)*m%v_m_s(i) + f*m%v_m_s(i + 1)
      a = (1.0_dp - f)*m%a_m_s2(i) + f*m%a_m_s2(i + 1)
    case (waveform_accelerogram)
      call accelerogram_eval(m%a_m_s2, m%v_m_s, m%x_m, m%dt_record_s, t_s - m%start_s, x, v, a)
    end select
  end subroutine motion_eval

  !> Vertical table displacement [m], velocity [m/s] and acceleration [m/s2], upwards,
  !> at time `t_s` (zero without a vertical component).
  pure subroutine motion_eval_vertical(m, t_s, y, vy, ay)
    type(motion_t), intent(in) :: m
    real(dp), intent(in) :: t_s
    real(dp), intent(out) :: y, vy, ay
    select case (m%vertical)
    case (vertical_ratio_of_afd)
      call motion_eval(m, t_s, y, vy, ay)
      y = m%vertical_ratio*y
      vy = m%vertical_ratio*vy
      ay = m%vertical_ratio*ay
    case (vertical_samples)
      call accelerogram_eval(m%ay_m_s2, m%vy_m_s, m%y_m, m%dt_record_s, t_s - m%start_s, y, vy, ay)
    case default
      y = 0.0_dp
      vy = 0.0_dp
      ay = 0.0_dp
    end select
  end subroutine motion_eval_vertical

  !> The accelerogram of samples `a` (linear between them, `dt_s` apart) and their exact
  !> integrals `v`, `x` at time `t` after its first sample (at rest before it).
  pure subroutine accelerogram_eval(a_s, v_s, x_s, dt_s, t, x, v, a)
    real(dp), intent(in) :: a_s(:), v_s(:), x_s(:), dt_s, t
    real(dp), intent(out) :: x, v, a
    real(dp) :: tau, slope
    integer :: i, n
    x = 0.0_dp
    v = 0.0_dp
    a = 0.0_dp
    if (t < 0.0_dp) return
    n = size(a_s)
    i = min(int(t/dt_s) + 1, n)
    tau = t - (i - 1)*dt_s
    if (i == n) then
      ! After the last sample (or on it): no acceleration, constant velocity.
      x = x_s(n) + v_s(n)*tau
      v = v_s(n)
      if (tau == 0.0_dp) a = a_s(n)
      return
    end if
    slope = (a_s(i + 1) - a_s(i))/dt_s
    a = a_s(i) + slope*tau
    v = v_s(i) + a_s(i)*tau + slope*tau*tau/2.0_dp
    x = x_s(i) + v_s(i)*tau + a_s(i)*tau*tau/2.0_dp + slope*tau**3/6.0_dp
  end subroutine accelerogram_eval

  !> An afd motion's vertical component: `ratio` times its horizontal one.
  pure subroutine motion_set_vertical_ratio(m, ratio)
    type(motion_t), intent(inout) :: m
    real(dp), intent(in) :: ratio
    m%vertical = vertical_ratio_of_afd
    m%vertical_ratio = ratio
  end subroutine motion_set_vertical_ratio

  !> An accelerogram's vertical component: the samples `accel_m_s2` (upwards, already
  !> scaled) on the horizontal's time steps, as many as the horizontal has.
  pure subroutine motion_set_vertical_record(m, accel_m_s2)
    type(motion_t), intent(inout) :: m
    real(dp), intent(in) :: accel_m_s2(:)
    m%vertical = vertical_samples
    m%ay_m_s2 = accel_m_s2
    m%vy_m_s = accel_m_s2   ! (sized as the samples; the integrals overwrite them)
    m%y_m = accel_m_s2
    call integrate_linear_accel(m%ay_m_s2, m%dt_record_s, m%vy_m_s, m%y_m)
  end subroutine motion_set_vertical_record

  !> Read a measured table record (CSV with a header naming `t_s` and `table_x_m`; `#`
  !> comment lines), low-pass filter it at `cutoff_hz` and differentiate it.
  subroutine motion_record(path, cutoff_hz, m, status)
    character(len=*), intent(in) :: path
    real(dp), intent(in) :: cutoff_hz
    type(motion_t), intent(out) :: m
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: t(:), x(:), columns(:, :)
    integer, allocatable :: lines(:)
    real(dp) :: dt
    integer :: n, i

    call read_csv_columns(path, [character(len=16) :: 't_s', 'table_x_m'], columns, lines, status)
    if (.not. status%ok) return
    t = columns(1, :)
    x = columns(2, :)
    n = size(t)
    if (n < 3) then
      call fail(status, trim(path)//': a record needs at least 3 samples')
      return
    end if
    dt = (t(n) - t(1))/(n - 1)
    if (dt <= 0.0_dp) then
      call fail(status, trim(path)//': t_s must increase')
      return
    end if
    do i = 2, n
      if (abs(t(i) - t(i - 1) - dt) > 1.0e-3_dp*dt) then
        call fail(status, trim(path)//': t_s is not uniformly sampled')
        return
      end if
    end do
    m%waveform = waveform_record
    m%dt_record_s = dt
    x = x - x(1)
    if (cutoff_hz > 0.0_dp .and. cutoff_hz < 0.5_dp/dt) call filtfilt_butter2(x, cutoff_hz*dt)
    allocate (m%v_m_s(n), m%a_m_s2(n))
    m%v_m_s(2:n - 1) = (x(3:n) - x(1:n - 2))/(2.0_dp*dt)
    m%v_m_s(1) = (x(2) - x(1))/dt
    m%v_m_s(n) = (x(n) - x(n - 1))/dt
    m%a_m_s2(2:n - 1) = (x(3:n) - 2.0_dp*x(2:n - 1) + x(1:n - 2))/dt**2
    m%a_m_s2(1) = 0.0_dp
    m%a_m_s2(n) = 0.0_dp
    call move_alloc(x, m%x_m)
  end subroutine motion_record

  !> Zero-phase second-order Butterworth low-pass (forward and backward) in place;
  !> `fc` is the cut-off frequency times the sampling interval.
  pure subroutine filtfilt_butter2(x, fc)
    real(dp), intent(inout) :: x(:)
    real(dp), intent(in) :: fc
    real(dp) :: k, norm, b0, b1, b2, a1, a2, offset
    k = tan(pi*fc)
    norm = 1.0_dp/(1.0_dp + sqrt(2.0_dp)*k + k*k)
    b0 = k*k*norm
    b1 = 2.0_dp*b0
    b2 = b0
    a1 = 2.0_dp*(k*k - 1.0_dp)*norm
    a2 = (1.0_dp - sqrt(2.0_dp)*k + k*k)*norm
    offset = x(1)
    x = x - offset
    call pass(x)
    x = x + offset
    offset = x(size(x))
    x = x(size(x):1:-1) - offset
    call pass(x)
    x = x(size(x):1:-1) + offset
  contains
    pure subroutine pass(y)
      real(dp), intent(inout) :: y(:)
      real(dp) :: x1, x2, y1, y2, x0
      integer :: i
      x1 = 0.0_dp; x2 = 0.0_dp; y1 = 0.0_dp; y2 = 0.0_dp
      do i = 1, size(y)
        x0 = y(i)
        y(i) = b0*x0 + b1*x1 + b2*x2 - a1*y1 - a2*y2
        x2 = x1; x1 = x0
        y2 = y1; y1 = y(i)
      end do
    end subroutine pass
  end subroutine filtfilt_butter2

end module voussoir_motion
