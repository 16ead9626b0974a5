!> Collapse threshold of one case at one frequency: the smallest commanded `afd`
!> amplitude that brings the arch down, to a tolerance.
!>
!> The search is a state machine, so that a caller can run its simulations anywhere
!> (here in `find_threshold`, or spread over MPI ranks by voussoir-sweep) and replay
!> recorded outcomes to resume: `threshold_next` proposes the next amplitude,
!> `threshold_record` takes its outcome. The sequence of amplitudes depends only on the
!> outcomes, never on timing, so a search gives the same answer wherever it runs.
!>
!> Phases (docs/sweep.md explains the trade-offs):
!>
!> 1. start: one run at `start_fraction` of the static onset amplitude, the amplitude
!>    whose peak table acceleration equals the limit-analysis capacity lambda g (below it
!>    a rigid arch does not move). If that run stands still ("quiet": peak crown
!>    displacement below the hinge gap), no collapse can hide below it: the table
!>    acceleration scales with the amplitude.
!> 2. descend (only when there is no estimate or the start run moved or fell): divide the
!>    amplitude by `descend_ratio` until a quiet run.
!> 3. scan: from the quiet amplitude upwards in steps of `scan_step` (a fraction of the
!>    amplitude) until the first collapse, or `amp_max_m`.
!> 4. refine: the bracket (last stand, first collapse) is cut into `refine_factor` equal
!>    parts (fewer when that reaches `amp_tol_m`) whose inner points are run from the
!>    bottom up; the first collapse and the point below it are the next bracket, until it
!>    is `amp_tol_m` wide. With `refine_factor` = 2 this is plain bisection; a larger
!>    factor looks at each bracket from below, so that a safe island inside the bracket
!>    does not lead it to the upper edge of the island instead of the first collapse.
!> 5. confirm: `n_confirm` runs just above the threshold (steps of
!>    scan_step / refine_factor), to meet safe islands if there are any.
!>
!> The threshold is the collapsing end of the final bracket: the first collapse from
!> below. Any stand met above it sets `non_monotonic`.
module voussoir_threshold
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp, pi, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_config, only: config_t, fmt_real
  use voussoir_assembly, only: assembly_t, build_arch, voussoir_angle_factors
  use voussoir_limit_analysis, only: limit_result_t, horizontal_capacity
  use voussoir_motion, only: motion_t, motion_afd, motion_eval, motion_duration_s
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: run_config
  implicit none
  private

  public :: threshold_settings_t, run_outcome_t, threshold_search_t, threshold_result_t
  public :: check_threshold_settings, threshold_init, threshold_next, threshold_record
  public :: threshold_result, threshold_done, find_threshold, search_run_config
  public :: outcome_of_run, static_onset_amplitude_m, afd_peak_accel_per_m, static_capacity_m_s2
  public :: threshold_init_onset
  public :: phase_start, phase_descend, phase_scan, phase_refine, phase_confirm, phase_done

  integer, parameter :: phase_start = 1    !! first run, just below the static onset
  integer, parameter :: phase_descend = 2  !! looking downwards for a quiet run
  integer, parameter :: phase_scan = 3     !! upward scan to the first collapse
  integer, parameter :: phase_refine = 4   !! upward scans of ever finer brackets
  integer, parameter :: phase_confirm = 5  !! probes just above the threshold
  integer, parameter :: phase_done = 6     !! the answer is known

  !> Samples per cycle when the peak acceleration of the afd waveform is measured.
  integer, parameter :: samples_per_cycle = 2000
  !> Output interval of a search run [steps]: no time series is needed.
  integer, parameter :: no_samples = huge(1)

  !> How a search proceeds; the defaults suit the seed arches.
  type :: threshold_settings_t
    real(dp) :: amp_tol_m = 2.5e-4_dp      !! width of the final bracket [m]
    real(dp) :: amp_max_m = 0.5_dp         !! largest amplitude tried [m]
    real(dp) :: scan_step = 0.10_dp        !! upward scan step, fraction of the amplitude
    integer :: refine_factor = 4           !! parts a bracket is cut into (2: bisection)
    real(dp) :: start_fraction = 0.95_dp   !! first run, fraction of the static onset
    real(dp) :: descend_ratio = 2.0_dp     !! divisor of the downward search
    integer :: n_confirm = 2               !! probes just above the threshold
    !> amp_tol_m is relative to the collapsing end of the bracket (the scale of a record,
    !> which has no unit); the smallest value tried is then amp_max_m / 1000
    logical :: relative_tol = .false.
  end type threshold_settings_t

  !> What one run tells the search (and what a sweep records of it).
  type :: run_outcome_t
    real(dp) :: amplitude_m = 0.0_dp
    logical :: collapsed = .false.
    real(dp) :: collapse_time_s = 0.0_dp    !! NaN when it stood
    real(dp) :: peak_crown_disp_m = 0.0_dp
    real(dp) :: mean_iterations = 0.0_dp
    integer :: n_steps = 0
    integer :: nonconverged_steps = 0
    real(dp) :: wall_time_s = 0.0_dp
    logical :: failed = .false.             !! the run stopped with an error (the sweep goes on)
  end type run_outcome_t

  !> The state of one search.
  type :: threshold_search_t
    type(threshold_settings_t) :: settings
    real(dp) :: frequency_hz = 0.0_dp
    real(dp) :: onset_amp_m = 0.0_dp     !! static onset amplitude [m]; 0 if unknown
    real(dp) :: quiet_disp_m = 0.0_dp    !! peak crown displacement of a still arch [m]
    integer :: phase = phase_start
    real(dp) :: lo_m = 0.0_dp            !! largest stand of the bracket [m]
    real(dp) :: hi_m = 0.0_dp            !! smallest collapse of the bracket [m]
    real(dp) :: next_m = 0.0_dp          !! amplitude of the next run [m]
    real(dp) :: level_lo_m = 0.0_dp      !! bracket being refined [m]
    real(dp) :: level_hi_m = 0.0_dp
    integer :: level_parts = 2           !! parts of the bracket being refined
    integer :: level_point = 1           !! inner point being run (1 .. level_parts - 1)
    integer :: n_confirmed = 0
    integer :: n_runs = 0
    type(run_outcome_t), allocatable :: runs(:)
  end type threshold_search_t

  !> The answer of a search.
  type :: threshold_result_t
    real(dp) :: frequency_hz = 0.0_dp
    real(dp) :: threshold_m = 0.0_dp     !! first collapse from below; NaN if none up to amp_max_m
    real(dp) :: stand_below_m = 0.0_dp   !! largest stand below the threshold [m]
    real(dp) :: peak_accel_m_s2 = 0.0_dp !! threshold_m (2 pi f)^2; NaN if none
    logical :: non_monotonic = .false.   !! a stand was met above a collapse
    integer :: n_runs = 0
    real(dp) :: mean_iterations = 0.0_dp !! NLGS iterations per step over all runs
    real(dp) :: wall_time_s = 0.0_dp     !! sum over the runs
    real(dp) :: onset_amp_m = 0.0_dp     !! static onset amplitude used to start [m]
  end type threshold_result_t

contains

  !> Check `settings`; messages name the setting and its allowed range.
  subroutine check_threshold_settings(settings, status)
    type(threshold_settings_t), intent(in) :: settings
    type(status_t), intent(inout) :: status
    associate (s => settings)
      if (.not. (s%amp_tol_m > 0.0_dp)) then
        call fail(status, 'threshold search: amp_tol_m = '//fmt_real(s%amp_tol_m)//' must be > 0')
      else if (s%relative_tol .and. .not. (s%amp_tol_m < 1.0_dp .and. s%amp_max_m > 0.0_dp)) then
        call fail(status, 'threshold search: a relative tolerance '//fmt_real(s%amp_tol_m)// &
                  ' must be < 1, and the largest value '//fmt_real(s%amp_max_m)//' > 0')
      else if (.not. s%relative_tol .and. .not. (s%amp_max_m > s%amp_tol_m)) then
        call fail(status, 'threshold search: amp_max_m = '//fmt_real(s%amp_max_m)// &
                  ' must be > amp_tol_m = '//fmt_real(s%amp_tol_m))
      else if (.not. (s%scan_step > 0.0_dp .and. s%scan_step <= 1.0_dp)) then
        call fail(status, 'threshold search: scan_step = '//fmt_real(s%scan_step)//' must be in (0, 1]')
      else if (.not. (s%start_fraction > 0.0_dp .and. s%start_fraction <= 1.0_dp)) then
        call fail(status, 'threshold search: start_fraction = '//fmt_real(s%start_fraction)// &
                  ' must be in (0, 1]')
      else if (.not. (s%descend_ratio > 1.0_dp)) then
        call fail(status, 'threshold search: descend_ratio = '//fmt_real(s%descend_ratio)//' must be > 1')
      else if (s%refine_factor < 2) then
        call fail(status, 'threshold search: refine_factor must be >= 2')
      else if (s%n_confirm < 0) then
        call fail(status, 'threshold search: n_confirm must be >= 0')
      end if
    end associate
  end subroutine check_threshold_settings

  !> The configuration of one search run: `base` at `frequency_hz` and `amplitude_m`,
  !> stopping at the collapse and keeping no time series.
  pure function search_run_config(base, frequency_hz, amplitude_m) result(cfg)
    type(config_t), intent(in) :: base
    real(dp), intent(in) :: frequency_hz, amplitude_m
    type(config_t) :: cfg
    cfg = base
    cfg%motion%frequency_hz = frequency_hz
    cfg%motion%amplitude_m = amplitude_m
    cfg%output%stop_after_collapse_s = 0.0_dp
    cfg%output%every = no_samples
  end function search_run_config

  !> The outcome of a finished run at `amplitude_m`.
  pure function outcome_of_run(amplitude_m, res) result(outcome)
    real(dp), intent(in) :: amplitude_m
    type(run_result_t), intent(in) :: res
    type(run_outcome_t) :: outcome
    outcome%amplitude_m = amplitude_m
    outcome%collapsed = res%collapsed
    outcome%collapse_time_s = res%collapse_time_s
    outcome%peak_crown_disp_m = res%peak_crown_disp_m
    outcome%mean_iterations = res%mean_iterations
    outcome%n_steps = res%n_steps
    outcome%nonconverged_steps = res%nonconverged_steps
    outcome%wall_time_s = res%wall_time_s
  end function outcome_of_run

  !> Largest |table acceleration| [m/s2] of the afd motion of `cfg` at `frequency_hz`,
  !> per metre of amplitude (slightly above (2 pi f)^2: the envelopes add to it).
  pure real(dp) function afd_peak_accel_per_m(cfg, frequency_hz)
    type(config_t), intent(in) :: cfg
    real(dp), intent(in) :: frequency_hz
    type(motion_t) :: m
    integer :: i, n
    real(dp) :: x, v, a, t_end_s
    m = motion_afd(frequency_hz, 1.0_dp, cfg%motion%n_attack, cfg%motion%n_full, cfg%motion%n_decay)
    t_end_s = motion_duration_s(m)
    n = samples_per_cycle*(cfg%motion%n_attack + cfg%motion%n_full + cfg%motion%n_decay)
    afd_peak_accel_per_m = 0.0_dp
    do i = 0, n
      call motion_eval(m, t_end_s*real(i, dp)/real(n, dp), x, v, a)
      afd_peak_accel_per_m = max(afd_peak_accel_per_m, abs(a))
    end do
  end function afd_peak_accel_per_m

  !> Amplitude [m] at which the peak afd table acceleration reaches the horizontal
  !> collapse capacity lambda g of the limit analysis: below it the rigid arch does not
  !> move. 0 when it does not apply (polygon assemblies, restraint brackets, no capacity).
  real(dp) function static_onset_amplitude_m(cfg, frequency_hz) result(amp_m)
    type(config_t), intent(in) :: cfg
    real(dp), intent(in) :: frequency_hz
    amp_m = static_capacity_m_s2(cfg)
    if (amp_m > 0.0_dp) amp_m = amp_m/afd_peak_accel_per_m(cfg, frequency_hz)
  end function static_onset_amplitude_m

  !> The horizontal collapse capacity lambda g [m/s2] of the arch of `cfg` (limit
  !> analysis, the weaker direction); 0 when it does not apply (polygon assemblies,
  !> restraint brackets, no capacity).
  real(dp) function static_capacity_m_s2(cfg) result(capacity)
    type(config_t), intent(in) :: cfg
    type(assembly_t) :: arch
    type(limit_result_t) :: limit
    type(status_t) :: status
    real(dp) :: lambda

    capacity = 0.0_dp
    if (len_trim(cfg%arch%polygon_file) > 0 .or. cfg%arch%restrained_springings /= 'none') return
    if (cfg%arch%n_voussoirs < 3) return
    call build_arch(cfg%arch%embrace_deg, cfg%arch%n_voussoirs, cfg%arch%r_ext_m, cfg%arch%thickness_m, arch, &
                    angle_factors=voussoir_angle_factors(cfg%arch%n_voussoirs, cfg%arch%size_imperfection, &
                                                         cfg%arch%imperfection_seed))
    call horizontal_capacity(arch, cfg%arch%contact_inset_m, cfg%arch%friction, limit, status)
    if (.not. status%ok) return
    lambda = min(limit%lambda_pos, limit%lambda_neg)
    if (.not. (lambda > 0.0_dp .and. lambda < huge(1.0_dp))) return
    capacity = lambda*g_m_s2
  end function static_capacity_m_s2

  !> A new search for the case `cfg` (an afd motion) at `frequency_hz`.
  subroutine threshold_init(search, cfg, frequency_hz, settings, status)
    type(threshold_search_t), intent(out) :: search
    type(config_t), intent(in) :: cfg
    real(dp), intent(in) :: frequency_hz
    type(threshold_settings_t), intent(in) :: settings
    type(status_t), intent(inout) :: status

    call check_threshold_settings(settings, status)
    if (.not. status%ok) return
    if (cfg%motion%waveform /= 'afd') then
      call fail(status, "threshold search: &motion waveform = '"//trim(cfg%motion%waveform)// &
                "' has no amplitude to search; it must be 'afd'")
      return
    end if
    if (.not. (frequency_hz > 0.0_dp)) then
      call fail(status, 'threshold search: frequency_hz = '//fmt_real(frequency_hz)//' must be > 0')
      return
    end if
    call threshold_init_onset(search, cfg, static_onset_amplitude_m(cfg, frequency_hz), settings, status)
    search%frequency_hz = frequency_hz
  end subroutine threshold_init

  !> A new search for the case `cfg` over a variable (an amplitude, a scale) below
  !> `onset` of which the arch does not move (0: unknown).
  subroutine threshold_init_onset(search, cfg, onset, settings, status)
    type(threshold_search_t), intent(out) :: search
    type(config_t), intent(in) :: cfg
    real(dp), intent(in) :: onset
    type(threshold_settings_t), intent(in) :: settings
    type(status_t), intent(inout) :: status
    call check_threshold_settings(settings, status)
    if (.not. status%ok) return
    search%settings = settings
    search%quiet_disp_m = cfg%output%hinge_gap_m
    if (search%quiet_disp_m <= 0.0_dp) search%quiet_disp_m = 0.01_dp*cfg%arch%thickness_m
    search%onset_amp_m = onset
    allocate (search%runs(16))
    if (search%onset_amp_m > 0.0_dp) then
      search%phase = phase_start
      search%next_m = min(settings%start_fraction*search%onset_amp_m, settings%amp_max_m)
    else
      ! No estimate: come down from the top until the arch stays still.
      search%phase = phase_descend
      search%next_m = settings%amp_max_m
    end if
  end subroutine threshold_init_onset

  !> Whether the search has its answer.
  pure logical function threshold_done(search)
    type(threshold_search_t), intent(in) :: search
    threshold_done = search%phase == phase_done
  end function threshold_done

  !> The amplitude [m] of the next run, or `done` when the search has its answer.
  !> Asking twice without recording gives the same amplitude.
  pure subroutine threshold_next(search, amplitude_m, done)
    type(threshold_search_t), intent(in) :: search
    real(dp), intent(out) :: amplitude_m
    logical, intent(out) :: done
    done = search%phase == phase_done
    amplitude_m = 0.0_dp
    if (.not. done) amplitude_m = search%next_m
  end subroutine threshold_next

  !> Take the outcome of the run at the amplitude `threshold_next` proposed.
  subroutine threshold_record(search, outcome, status)
    type(threshold_search_t), intent(inout) :: search
    type(run_outcome_t), intent(in) :: outcome
    type(status_t), intent(inout) :: status
    real(dp) :: a
    logical :: quiet

    if (search%phase == phase_done) then
      call fail(status, 'threshold search: an outcome was recorded after the search ended')
      return
    end if
    if (outcome%amplitude_m /= search%next_m) then
      call fail(status, 'threshold search: the outcome at amplitude_m = '//fmt_real(outcome%amplitude_m)// &
                ' is not that of the proposed run at '//fmt_real(search%next_m))
      return
    end if
    if (search%n_runs == size(search%runs)) search%runs = [search%runs, search%runs]
    search%n_runs = search%n_runs + 1
    search%runs(search%n_runs) = outcome
    a = outcome%amplitude_m
    quiet = .not. outcome%collapsed .and. outcome%peak_crown_disp_m < search%quiet_disp_m

    associate (s => search%settings)
      select case (search%phase)
      case (phase_start, phase_descend)
        if (quiet) then
          search%lo_m = a
          call enter_scan()
        else if (a/s%descend_ratio < smallest_value()) then
          ! Moving even at the smallest amplitude worth trying.
          if (outcome%collapsed) then
            search%lo_m = 0.0_dp
            search%hi_m = a
            call enter_refine()
          else
            search%lo_m = a
            call enter_scan()
          end if
        else
          search%phase = phase_descend
          search%next_m = a/s%descend_ratio
        end if
      case (phase_scan)
        if (outcome%collapsed) then
          search%hi_m = a
          call enter_refine()
        else
          search%lo_m = a
          call enter_scan()
        end if
      case (phase_refine)
        if (outcome%collapsed) then
          search%hi_m = a
          call enter_refine()
        else
          search%lo_m = a
          if (search%level_point < search%level_parts - 1) then
            search%level_point = search%level_point + 1
            search%next_m = refine_point()
          else
            call enter_refine()   ! the whole level stood: its top part is the bracket
          end if
        end if
      case (phase_confirm)
        search%n_confirmed = search%n_confirmed + 1
        call enter_confirm()
      end select
    end associate

  contains

    !> Next scan amplitude above `lo_m`, or the bracket when it reaches a known collapse.
    subroutine enter_scan()
      real(dp) :: next_m, known_m
      associate (s => search%settings)
        search%phase = phase_scan
        if (search%lo_m >= s%amp_max_m) then
          search%phase = phase_done   ! stood up to amp_max_m
          return
        end if
        next_m = min(search%lo_m*(1.0_dp + s%scan_step), s%amp_max_m)
        if (search%lo_m == 0.0_dp) next_m = smallest_value()
        known_m = smallest_collapse_above(search%lo_m)
        if (known_m > 0.0_dp .and. next_m >= known_m) then
          ! A collapse met on the way down bounds the scan.
          search%hi_m = known_m
          call enter_refine()
          return
        end if
        search%next_m = next_m
      end associate
    end subroutine enter_scan

    !> The smallest amplitude worth trying: the tolerance, or amp_max_m / 1000 for a
    !> relative one.
    real(dp) function smallest_value()
      smallest_value = merge(1.0e-3_dp*search%settings%amp_max_m, search%settings%amp_tol_m, &
                             search%settings%relative_tol)
    end function smallest_value

    !> A new level on the bracket (lo_m, hi_m), or the confirmation once it is narrow.
    subroutine enter_refine()
      real(dp) :: width_m, tol_m
      search%phase = phase_refine
      width_m = search%hi_m - search%lo_m
      tol_m = merge(search%settings%amp_tol_m*search%hi_m, search%settings%amp_tol_m, search%settings%relative_tol)
      if (width_m <= tol_m) then
        call enter_confirm()
        return
      end if
      search%level_lo_m = search%lo_m
      search%level_hi_m = search%hi_m
      ! Never finer than needed to reach the tolerance in this level.
      search%level_parts = int(min(real(search%settings%refine_factor, dp), &
                                   real(ceiling(width_m/tol_m - 1.0e-9_dp), dp)))
      search%level_parts = max(2, search%level_parts)
      search%level_point = 1
      search%next_m = refine_point()
    end subroutine enter_refine

    real(dp) function refine_point()
      refine_point = search%level_lo_m + (search%level_hi_m - search%level_lo_m)* &
                     real(search%level_point, dp)/real(search%level_parts, dp)
    end function refine_point

    subroutine enter_confirm()
      real(dp) :: probe_m, step
      search%phase = phase_confirm
      step = search%settings%scan_step/search%settings%refine_factor
      do while (search%n_confirmed < search%settings%n_confirm)
        probe_m = search%hi_m*(1.0_dp + step*(search%n_confirmed + 1))
        if (probe_m > search%settings%amp_max_m) exit
        if (.not. already_run(probe_m)) then
          search%next_m = probe_m
          return
        end if
        search%n_confirmed = search%n_confirmed + 1
      end do
      search%phase = phase_done
    end subroutine enter_confirm

    real(dp) function smallest_collapse_above(lo_m) result(amp_m)
      real(dp), intent(in) :: lo_m
      integer :: k
      amp_m = 0.0_dp
      do k = 1, search%n_runs
        if (.not. search%runs(k)%collapsed .or. search%runs(k)%amplitude_m <= lo_m) cycle
        if (amp_m == 0.0_dp .or. search%runs(k)%amplitude_m < amp_m) amp_m = search%runs(k)%amplitude_m
      end do
    end function smallest_collapse_above

    logical function already_run(amp_m)
      real(dp), intent(in) :: amp_m
      already_run = any(search%runs(1:search%n_runs)%amplitude_m == amp_m)
    end function already_run

  end subroutine threshold_record

  !> The answer of a finished search (provisional while it runs).
  pure function threshold_result(search) result(r)
    type(threshold_search_t), intent(in) :: search
    type(threshold_result_t) :: r
    real(dp) :: nan, steps
    integer :: k
    nan = ieee_value(1.0_dp, ieee_quiet_nan)
    r%frequency_hz = search%frequency_hz
    r%n_runs = search%n_runs
    r%onset_amp_m = search%onset_amp_m
    if (search%hi_m > 0.0_dp) then
      r%threshold_m = search%hi_m
      r%stand_below_m = search%lo_m
      r%peak_accel_m_s2 = search%hi_m*(2.0_dp*pi*search%frequency_hz)**2
    else
      r%threshold_m = nan
      r%stand_below_m = search%lo_m
      r%peak_accel_m_s2 = nan
    end if
    steps = 0.0_dp
    r%mean_iterations = 0.0_dp
    r%wall_time_s = 0.0_dp
    do k = 1, search%n_runs
      associate (o => search%runs(k))
        if (search%hi_m > 0.0_dp .and. .not. o%collapsed .and. o%amplitude_m > search%hi_m) &
          r%non_monotonic = .true.
        steps = steps + o%n_steps
        r%mean_iterations = r%mean_iterations + o%mean_iterations*o%n_steps
        r%wall_time_s = r%wall_time_s + o%wall_time_s
      end associate
    end do
    if (steps > 0.0_dp) r%mean_iterations = r%mean_iterations/steps
  end function threshold_result

  !> The whole search in this process: every run through `run_config`. `runs`, if
  !> present, returns the outcome of every run in the order they were made.
  subroutine find_threshold(cfg, frequency_hz, settings, result, status, runs)
    type(config_t), intent(in) :: cfg
    real(dp), intent(in) :: frequency_hz
    type(threshold_settings_t), intent(in) :: settings
    type(threshold_result_t), intent(out) :: result
    type(status_t), intent(inout) :: status
    type(run_outcome_t), allocatable, intent(out), optional :: runs(:)
    type(threshold_search_t) :: search
    type(assembly_t) :: assembly
    type(model_t) :: model
    type(run_result_t) :: res
    real(dp) :: amp_m
    logical :: done

    call threshold_init(search, cfg, frequency_hz, settings, status)
    if (.not. status%ok) return
    do
      call threshold_next(search, amp_m, done)
      if (done) exit
      call run_config(search_run_config(cfg, frequency_hz, amp_m), assembly, model, res, status)
      if (.not. status%ok) then
        status%message = 'threshold search at '//fmt_real(frequency_hz)//' Hz, amplitude '// &
                         fmt_real(amp_m)//' m: '//trim(status%message)
        return
      end if
      call threshold_record(search, outcome_of_run(amp_m, res), status)
      if (.not. status%ok) return
    end do
    result = threshold_result(search)
    if (present(runs)) runs = search%runs(1:search%n_runs)
  end subroutine find_threshold

end module voussoir_threshold
