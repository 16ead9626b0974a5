!> The threshold search as a state machine, without any simulation: the smallest value
!> of a variable (the commanded `afd` amplitude, or the scale of a record) that brings
!> the arch down, to a tolerance. The runs themselves are src/sweep/threshold.f90.
!>
!> A caller runs the simulations anywhere (serially in `find_threshold`, or spread over
!> MPI ranks by voussoir-sweep) and can replay recorded outcomes to resume:
!> `threshold_next` proposes the next amplitude, `threshold_record` takes its outcome. The sequence of amplitudes depends only on the
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
module voussoir_threshold_search
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use voussoir_kinds, only: dp, pi
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: fmt_real
  use voussoir_config, only: config_t
  implicit none
  private

  public :: threshold_settings_t, run_outcome_t, threshold_search_t, threshold_result_t
  public :: check_threshold_settings, threshold_init_onset, threshold_next, threshold_record
  public :: threshold_result, threshold_done
  public :: phase_start, phase_descend, phase_scan, phase_refine, phase_confirm, phase_done

  integer, parameter :: phase_start = 1    !! first run, just below the static onset
  integer, parameter :: phase_descend = 2  !! looking downwards for a quiet run
  integer, parameter :: phase_scan = 3     !! upward scan to the first collapse
  integer, parameter :: phase_refine = 4   !! upward scans of ever finer brackets
  integer, parameter :: phase_confirm = 5  !! probes just above the threshold
  integer, parameter :: phase_done = 6     !! the answer is known

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
    real(dp) :: peak_joint_opening_m = 0.0_dp   !! largest opening of an arch joint [m]
    real(dp) :: residual_crown_drift_m = 0.0_dp !! crown's horizontal drift from the table at the end [m]
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
  contains
    ! The transitions of the state machine (threshold_record calls them); public so that
    ! a test can reach each one.
    procedure :: after_start, after_scan, after_refine, enter_scan, enter_refine, enter_confirm
    procedure :: smallest_value, refine_point, smallest_collapse_above, already_run
  end type threshold_search_t

  !> The answer of a search.
  type :: threshold_result_t
    real(dp) :: frequency_hz = 0.0_dp
    real(dp) :: threshold_m = 0.0_dp     !! first collapse from below; NaN if none up to amp_max_m
    real(dp) :: stand_below_m = 0.0_dp   !! largest stand below the threshold [m]
    real(dp) :: full_cycle_accel_m_s2 = 0.0_dp !! threshold_m (2 pi f)^2 (not the afd peak); NaN if none
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

    select case (search%phase)
    case (phase_start, phase_descend)
      call search%after_start(a, quiet, outcome%collapsed)
    case (phase_scan)
      call search%after_scan(a, outcome%collapsed)
    case (phase_refine)
      call search%after_refine(a, outcome%collapsed)
    case (phase_confirm)
      search%n_confirmed = search%n_confirmed + 1
      call search%enter_confirm()
    end select
  end subroutine threshold_record

  !> Start or descend: a quiet run starts the scan; a run that moved or fell halves
  !> the value, down to the smallest one worth trying.
  subroutine after_start(search, a, quiet, collapsed)
    class(threshold_search_t), intent(inout) :: search
    real(dp), intent(in) :: a          !! the value just run
    logical, intent(in) :: quiet, collapsed
    if (quiet) then
      search%lo_m = a
      call search%enter_scan()
    else if (a/search%settings%descend_ratio < search%smallest_value()) then
      ! Moving even at the smallest amplitude worth trying.
      if (collapsed) search%lo_m = 0.0_dp
      call search%after_scan(a, collapsed)
    else
      search%phase = phase_descend
      search%next_m = a/search%settings%descend_ratio
    end if
  end subroutine after_start

  !> Scan: a collapse closes the bracket (refine it), a stand is its new bottom (scan on).
  subroutine after_scan(search, a, collapsed)
    class(threshold_search_t), intent(inout) :: search
    real(dp), intent(in) :: a          !! the value just run
    logical, intent(in) :: collapsed
    if (collapsed) then
      search%hi_m = a
      call search%enter_refine()
    else
      search%lo_m = a
      call search%enter_scan()
    end if
  end subroutine after_scan

  !> Refine: a collapse is the new top of the bracket; a stand moves to the next inner
  !> point of the level, or, at the last one, makes the level's top part the bracket.
  subroutine after_refine(search, a, collapsed)
    class(threshold_search_t), intent(inout) :: search
    real(dp), intent(in) :: a          !! the value just run
    logical, intent(in) :: collapsed
    if (collapsed) then
      search%hi_m = a
    else
      search%lo_m = a
      if (search%level_point < search%level_parts - 1) then
        search%level_point = search%level_point + 1
        search%next_m = search%refine_point()
        return
      end if
      ! The whole level stood: its top part is the bracket.
    end if
    call search%enter_refine()
  end subroutine after_refine

  !> Next scan amplitude above `lo_m`, or the bracket when it reaches a known collapse.
  subroutine enter_scan(search)
    class(threshold_search_t), intent(inout) :: search
    real(dp) :: next_m, known_m
    associate (s => search%settings)
      search%phase = phase_scan
      if (search%lo_m >= s%amp_max_m) then
        search%phase = phase_done   ! stood up to amp_max_m
        return
      end if
      next_m = min(search%lo_m*(1.0_dp + s%scan_step), s%amp_max_m)
      if (search%lo_m == 0.0_dp) next_m = search%smallest_value()
      known_m = search%smallest_collapse_above(search%lo_m)
      if (known_m > 0.0_dp .and. next_m >= known_m) then
        ! A collapse met on the way down bounds the scan.
        search%hi_m = known_m
        call search%enter_refine()
        return
      end if
      search%next_m = next_m
    end associate
  end subroutine enter_scan

  !> The smallest amplitude worth trying: the tolerance, or amp_max_m / 1000 for a
  !> relative one.
  pure real(dp) function smallest_value(search)
    class(threshold_search_t), intent(in) :: search
    smallest_value = merge(1.0e-3_dp*search%settings%amp_max_m, search%settings%amp_tol_m, &
                           search%settings%relative_tol)
  end function smallest_value

  !> A new level on the bracket (lo_m, hi_m), or the confirmation once it is narrow.
  subroutine enter_refine(search)
    class(threshold_search_t), intent(inout) :: search
    real(dp) :: width_m, tol_m
    search%phase = phase_refine
    width_m = search%hi_m - search%lo_m
    tol_m = merge(search%settings%amp_tol_m*search%hi_m, search%settings%amp_tol_m, search%settings%relative_tol)
    if (width_m <= tol_m) then
      call search%enter_confirm()
      return
    end if
    search%level_lo_m = search%lo_m
    search%level_hi_m = search%hi_m
    ! Never finer than needed to reach the tolerance in this level.
    search%level_parts = int(min(real(search%settings%refine_factor, dp), &
                                 real(ceiling(width_m/tol_m - 1.0e-9_dp), dp)))
    search%level_parts = max(2, search%level_parts)
    search%level_point = 1
    search%next_m = search%refine_point()
  end subroutine enter_refine

  !> The inner point `level_point` of the level being refined.
  pure real(dp) function refine_point(search)
    class(threshold_search_t), intent(in) :: search
    refine_point = search%level_lo_m + (search%level_hi_m - search%level_lo_m)* &
                   real(search%level_point, dp)/real(search%level_parts, dp)
  end function refine_point

  !> The next probe above the threshold not run yet, or done.
  subroutine enter_confirm(search)
    class(threshold_search_t), intent(inout) :: search
    real(dp) :: probe_m, step
    search%phase = phase_confirm
    step = search%settings%scan_step/search%settings%refine_factor
    do while (search%n_confirmed < search%settings%n_confirm)
      probe_m = search%hi_m*(1.0_dp + step*(search%n_confirmed + 1))
      if (probe_m > search%settings%amp_max_m) exit
      if (.not. search%already_run(probe_m)) then
        search%next_m = probe_m
        return
      end if
      search%n_confirmed = search%n_confirmed + 1
    end do
    search%phase = phase_done
  end subroutine enter_confirm

  !> The smallest collapse recorded above `lo_m` (0 if none).
  pure real(dp) function smallest_collapse_above(search, lo_m) result(amp_m)
    class(threshold_search_t), intent(in) :: search
    real(dp), intent(in) :: lo_m
    integer :: k
    amp_m = 0.0_dp
    do k = 1, search%n_runs
      if (.not. search%runs(k)%collapsed .or. search%runs(k)%amplitude_m <= lo_m) cycle
      if (amp_m == 0.0_dp .or. search%runs(k)%amplitude_m < amp_m) amp_m = search%runs(k)%amplitude_m
    end do
  end function smallest_collapse_above

  !> Whether a run at `amp_m` was made.
  pure logical function already_run(search, amp_m)
    class(threshold_search_t), intent(in) :: search
    real(dp), intent(in) :: amp_m
    already_run = any(search%runs(1:search%n_runs)%amplitude_m == amp_m)
  end function already_run

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
      r%full_cycle_accel_m_s2 = search%hi_m*(2.0_dp*pi*search%frequency_hz)**2
    else
      r%threshold_m = nan
      r%stand_below_m = search%lo_m
      r%full_cycle_accel_m_s2 = nan
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

end module voussoir_threshold_search
