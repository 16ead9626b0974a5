!> The collapse threshold search (src/sweep/threshold_search.f90, the runs src/sweep/threshold.f90).
!>
!> The state machine is driven by synthetic outcomes (a known threshold, a safe island,
!> no estimate of the onset, no collapse at all) so that its answers are exact; then one
!> real search on the seed's 156-degree arch is checked against single runs just below
!> and at the threshold it reports.
program test_threshold
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use voussoir_kinds, only: dp, pi, g_m_s2
  use voussoir_geometry, only: polygon_area, polygon_centroid
  use voussoir_status, only: status_t
  use voussoir_config, only: config_t
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: run_config
  use voussoir_threshold_search, only: threshold_settings_t, threshold_search_t, threshold_result_t, &
    run_outcome_t, check_threshold_settings, threshold_next, threshold_record, threshold_result
  use voussoir_threshold, only: threshold_init, find_threshold, search_run_config, static_onset_amplitude_m, &
    afd_peak_accel_per_m, static_capacity_m_s2
  use voussoir_assembly, only: build_arch, mirrored_blocks
  use voussoir_limit_lp_study, only: lp_study_t, lp_study
  use voussoir_limit_analysis, only: limit_result_t, horizontal_capacity
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  implicit none

  !> Limit-analysis multiplier of the seed's 156-degree arch (test_limit_analysis).
  real(dp), parameter :: lambda_156 = 0.37601921758948048_dp
  type(config_t) :: cfg
  type(threshold_settings_t) :: settings
  type(threshold_result_t) :: r
  type(status_t) :: status
  real(dp) :: onset_m, amps(64)
  integer :: n
  type(assembly_t) :: arch
  type(lp_study_t) :: pos, neg

  cfg = seed_156()

  ! Settings are checked.
  settings = threshold_settings_t()
  settings%amp_tol_m = 0.0_dp
  call check_threshold_settings(settings, status)
  call assert_true(.not. status%ok, 'amp_tol_m = 0 is refused')
  status = status_t()
  settings = threshold_settings_t()
  settings%refine_factor = 1
  call check_threshold_settings(settings, status)
  call assert_true(.not. status%ok, 'refine_factor = 1 is refused')
  status = status_t()

  ! The static onset amplitude: lambda g over the peak acceleration per metre.
  call assert_close(afd_peak_accel_per_m(cfg, 1.25_dp)/(2.0_dp*pi*1.25_dp)**2, 1.0491673_dp, &
                    'afd peak acceleration / A (2 pi f)^2 (1-1-1 cycles)', rtol=1.0e-5_dp)
  onset_m = static_onset_amplitude_m(cfg, 1.25_dp)
  call assert_close(onset_m, lambda_156*g_m_s2/afd_peak_accel_per_m(cfg, 1.25_dp), &
                    '156-degree arch, 1.25 Hz: static onset amplitude', rtol=1.0e-9_dp)

  ! Sliding: where the four-hinge field breaks Coulomb's law (friction 0.395, the
  ! diagnosis's fit of the seed arch) the capacity is the non-associative LP's, below the
  ! four-hinge one (voussoir-limit's driver test: below 0.9 lambda); at friction 0.5
  ! hinging governs and the capacity is the four-hinge one, exactly.
  call assert_close(static_capacity_m_s2(cfg), lambda_156*g_m_s2, 'friction 0.5: four-hinge capacity', &
                    rtol=1.0e-12_dp)
  cfg%arch%friction = 0.395_dp
  call build_arch(cfg%arch%embrace_deg, cfg%arch%n_voussoirs, cfg%arch%r_ext_m, cfg%arch%thickness_m, arch)
  call lp_study(arch, cfg%arch%density_kg_m3, cfg%arch%width_m, 0.395_dp, 0.0_dp, pos, status)
  call lp_study(mirrored_blocks(arch), cfg%arch%density_kg_m3, cfg%arch%width_m, 0.395_dp, 0.0_dp, neg, status)
  call assert_true(status%ok .and. pos%nonassociative_solved .and. neg%nonassociative_solved, &
                   'friction 0.395: both LPs solved')
  ! The arch is symmetric: pushed towards -x (its mirror towards +x) it holds the same.
  call assert_close(neg%nonassoc%load_factor, pos%nonassoc%load_factor, 'mirror: the same capacity', &
                    rtol=1.0e-9_dp)
  call assert_close(static_capacity_m_s2(cfg), pos%nonassoc%load_factor*g_m_s2, &
                    'friction 0.395: the capacity with sliding', rtol=1.0e-9_dp)
  call assert_true(static_capacity_m_s2(cfg) < 0.9_dp*lambda_156*g_m_s2, &
                   'friction 0.395: below 0.9 x the four-hinge capacity')
  cfg%arch%friction = 0.5_dp
  call test_loaded_capacity(cfg)
  call test_lp_only_capacities(cfg)

  ! Monotone case: collapse from 63.3 mm, still below 58 mm.
  settings = threshold_settings_t()
  call drive(cfg, settings, oracle_monotone, r, amps, n)
  call assert_true(r%threshold_m >= 0.0633_dp .and. r%threshold_m <= 0.0633_dp + settings%amp_tol_m, &
                   'monotone: threshold within amp_tol above the true one')
  call assert_true(r%threshold_m - r%stand_below_m <= settings%amp_tol_m, 'monotone: final bracket <= amp_tol')
  call assert_true(.not. r%non_monotonic, 'monotone: not flagged non-monotonic')
  call assert_close(amps(1), settings%start_fraction*onset_m, 'monotone: first run at 0.95 x onset', &
                    rtol=1.0e-12_dp)
  call assert_true(n <= 14, 'monotone: at most 14 runs')
  call assert_true(r%n_runs == n, 'monotone: n_runs counts the runs')
  call assert_close(r%full_cycle_accel_m_s2, r%threshold_m*(2.0_dp*pi*1.25_dp)**2, 'full_cycle_accel = A (2 pi f)^2', &
                    rtol=1.0e-12_dp)
  write (*, '(a,i0,a,f0.3,a)') '      ', n, ' runs, threshold ', 1.0e3_dp*r%threshold_m, ' mm'

  ! A collapse band 62.0-63.4 mm below a safe island 63.4-64.6 mm: the first collapse
  ! from below is found and the island is met by the confirmation.
  call drive(cfg, settings, oracle_island, r, amps, n)
  call assert_true(r%threshold_m >= 0.0620_dp .and. r%threshold_m <= 0.0620_dp + settings%amp_tol_m, &
                   'island: threshold is the first collapse from below')
  call assert_true(r%non_monotonic, 'island: flagged non-monotonic')
  write (*, '(a,i0,a,f0.3,a)') '      ', n, ' runs, threshold ', 1.0e3_dp*r%threshold_m, ' mm'

  ! A safe island in the middle of the scan's bracket (59.6, 65.5): collapse in
  ! [60.5, 62.0), stand in [62.0, 63.0), collapse from 63.0. Bisection tests the middle,
  ! 62.5, which stands, and follows the island's upper edge; the refinement from below
  ! tests 61.1 first and finds the first collapse.
  call drive(cfg, settings, oracle_mid_island, r, amps, n)
  call assert_true(r%threshold_m >= 0.0605_dp .and. r%threshold_m <= 0.0605_dp + settings%amp_tol_m, &
                   'island mid-bracket: refinement (factor 4) finds the first collapse')
  call assert_true(r%non_monotonic, 'island mid-bracket: flagged non-monotonic')
  settings%refine_factor = 2
  call drive(cfg, settings, oracle_mid_island, r, amps, n)
  call assert_true(r%threshold_m >= 0.0630_dp .and. r%threshold_m <= 0.0630_dp + settings%amp_tol_m, &
                   'island mid-bracket: bisection (factor 2) ends at the upper edge of the island')
  settings = threshold_settings_t()

  ! No onset estimate (a polygon file that is not there: no LP, no capacity): come down
  ! from amp_max_m.
  cfg%arch%polygon_file = 'no_such_ring.txt'
  call assert_true(static_onset_amplitude_m(cfg, 1.25_dp) == 0.0_dp, 'unreadable polygon file: no static estimate')
  call drive(cfg, settings, oracle_monotone, r, amps, n)
  call assert_close(amps(1), settings%amp_max_m, 'no estimate: first run at amp_max_m', rtol=1.0e-12_dp)
  call assert_true(r%threshold_m >= 0.0633_dp .and. r%threshold_m <= 0.0633_dp + settings%amp_tol_m, &
                   'no estimate: threshold within amp_tol')
  call assert_true(.not. r%non_monotonic, 'no estimate: collapses above are not non-monotonic')
  write (*, '(a,i0,a)') '      ', n, ' runs without an estimate'
  cfg%arch%polygon_file = ''

  ! Nothing collapses up to amp_max_m.
  settings%amp_max_m = 0.062_dp
  call drive(cfg, settings, oracle_monotone, r, amps, n)
  call assert_true(ieee_is_nan(r%threshold_m), 'stands up to amp_max_m: threshold NaN')
  call assert_close(maxval(amps(1:n)), settings%amp_max_m, 'stands up to amp_max_m: amp_max_m was run', &
                    rtol=1.0e-12_dp)
  settings = threshold_settings_t()

  ! An outcome for another amplitude than the proposed one is refused (resume safety).
  call refuse_foreign_outcome(cfg, settings)

  ! A real search, and single runs just below and at its threshold.
  call real_search()

  call assert_summary()

contains

  !> Assemblies the four-hinge analysis does not model start from the LP's capacity (the
  !> weaker direction, non-associative). The seed arch with restraint brackets, friction
  !> 10 (hinging governs): a left bracket leaves the least four-hinge mechanism with no
  !> hinge at joint 0, 0.3842135120804658 towards +x (the work equation over every set of
  !> four joints and sides, computed in Python as tests/limit/check_limit.py restrained
  !> does; -x: 0.6498); brackets at both springings fix the end voussoirs, leaving the
  !> 11 voussoirs of 12 degrees between them: the 132-degree seed arch, whose four-hinge
  !> lambda this is. A 3 x 3 wall of 0.2 x 0.1 m blocks at friction 0.3 < B/H = 2 slides
  !> on its foundation at lambda = mu (the &arch default arch's capacity was taken before).
  subroutine test_lp_only_capacities(base)
    type(config_t), intent(in) :: base
    type(config_t) :: c
    type(assembly_t) :: arch_132
    type(limit_result_t) :: exact
    type(status_t) :: status
    c = base
    c%arch%friction = 10.0_dp
    c%arch%restrained_springings = 'left'
    call assert_close(static_capacity_m_s2(c), 0.3842135120804658_dp*g_m_s2, &
                      'left bracket: the least four-hinge mechanism without a hinge at joint 0', rtol=1.0e-6_dp)
    c%arch%restrained_springings = 'both'
    call build_arch(132.0_dp, 11, c%arch%r_ext_m, c%arch%thickness_m, arch_132)
    call horizontal_capacity(arch_132, 0.0_dp, 10.0_dp, exact, status)
    call assert_true(status%ok, 'the 132-degree arch: four-hinge analysis')
    call assert_close(static_capacity_m_s2(c), min(exact%lambda_pos, exact%lambda_neg)*g_m_s2, &
                      'brackets at both springings: the four-hinge capacity of the 132-degree arch between them', &
                      rtol=1.0e-6_dp)
    c = base
    c%wall%courses = 3
    c%wall%blocks_per_course = 3
    c%wall%block_width_m = 0.2_dp
    c%wall%block_height_m = 0.1_dp
    c%arch%friction = 0.3_dp
    call assert_close(static_capacity_m_s2(c), 0.3_dp*g_m_s2, '3 x 3 wall, friction 0.3: slides at mu g', &
                      rtol=1.0e-9_dp)
    call test_polygon_file_capacity(base)
  end subroutine test_lp_only_capacities

  !> A polygon file's capacity is the LP's, its driven blocks the fixed supports: one
  !> block 0.2 m wide and 0.5 m tall on a driven base rocks about its toe at
  !> lambda = b / h = 0.4 when friction holds it (mu = 10), and slides at lambda = mu
  !> when friction is below b / h (mu = 0.25): the two closed forms of a rigid block.
  subroutine test_polygon_file_capacity(base)
    type(config_t), intent(in) :: base
    type(config_t) :: c
    character(len=*), parameter :: path = 'test_threshold_block.txt'
    integer :: unit
    open (newunit=unit, file=path, status='replace', action='write')
    write (unit, '(a)') '# a 0.2 x 0.5 m block on a driven base', 'block driven', '-0.5 -0.2', '0.7 -0.2', &
      '0.7 0', '-0.5 0', 'block free', '0 0', '0.2 0', '0.2 0.5', '0 0.5'
    close (unit)
    c = base
    c%arch%polygon_file = path
    c%arch%friction = 10.0_dp
    call assert_close(static_capacity_m_s2(c), 0.4_dp*g_m_s2, 'polygon file, one block: rocks at (b/h) g', &
                      rtol=1.0e-9_dp)
    c%arch%friction = 0.25_dp
    call assert_close(static_capacity_m_s2(c), 0.25_dp*g_m_s2, 'polygon file, one block, mu < b/h: slides at mu g', &
                      rtol=1.0e-9_dp)
    open (newunit=unit, file=path, status='old')
    close (unit, status='delete')
  end subroutine test_polygon_file_capacity

  !> &load in the sweep's static capacity (issue 25). A dead vertical load k W_i at the
  !> centroid of every voussoir i makes gravity 1 + k times stronger while the
  !> acceleration still acts on the masses alone: every force scales, the capacity is
  !> (1 + k) lambda g exactly (hinging still governs: the shear ratios do not change). A
  !> dead load on a foundation goes to the table: no change. The runs of a search keep
  !> the loads.
  subroutine test_loaded_capacity(base)
    type(config_t), intent(in) :: base
    real(dp), parameter :: k = 0.5_dp
    type(config_t) :: c, run_cfg
    type(assembly_t) :: arch
    real(dp) :: xy(2)
    integer :: i, n
    n = base%arch%n_voussoirs
    call build_arch(base%arch%embrace_deg, n, base%arch%r_ext_m, base%arch%thickness_m, arch)
    c = base
    do i = 1, n
      xy = polygon_centroid(arch%polygon(i)%xy)
      c%load%point_load_n(i) = k*c%arch%density_kg_m3*polygon_area(arch%polygon(i)%xy)*c%arch%width_m*g_m_s2
      c%load%point_load_x_m(i) = xy(1)
      c%load%point_load_y_m(i) = xy(2)
      c%load%point_load_live(i) = .false.
    end do
    c%load%n_point_loads = n
    call assert_close(static_capacity_m_s2(c), (1.0_dp + k)*lambda_156*g_m_s2, &
                      '&load: dead loads k W_i at the centroids: capacity (1 + k) lambda g', rtol=1.0e-9_dp)
    run_cfg = search_run_config(c, 1.25_dp, 0.01_dp)
    call assert_true(run_cfg%load%n_point_loads == n, '&load: the runs of a search keep the loads')
    c = base
    xy = polygon_centroid(arch%polygon(n + 1)%xy)
    c%load%point_load_n(1) = 1000.0_dp
    c%load%point_load_x_m(1) = xy(1)
    c%load%point_load_y_m(1) = xy(2)
    c%load%point_load_live(1) = .false.
    c%load%n_point_loads = 1
    call assert_close(static_capacity_m_s2(c), lambda_156*g_m_s2, '&load: a load on a foundation: lambda g', &
                      rtol=1.0e-9_dp)
  end subroutine test_loaded_capacity

  function seed_156() result(c)
    type(config_t) :: c
    c%arch%embrace_deg = 156.0_dp
    c%arch%n_voussoirs = 13
    c%output%hinge_gap_m = 0.01_dp*c%arch%thickness_m
    c%output%collapse_drop_m = 0.5_dp*c%arch%thickness_m
  end function seed_156

  !> Collapse from 63.3 mm; the arch does not move below 58 mm.
  subroutine oracle_monotone(amp_m, o)
    real(dp), intent(in) :: amp_m
    type(run_outcome_t), intent(out) :: o
    o%amplitude_m = amp_m
    o%collapsed = amp_m >= 0.0633_dp
    o%peak_crown_disp_m = merge(0.0_dp, 5.0e-3_dp, amp_m < 0.058_dp)
    o%n_steps = 100
    o%mean_iterations = 10.0_dp
  end subroutine oracle_monotone

  !> Collapse in [62.0, 63.4) mm and from 64.6 mm; a safe island between.
  subroutine oracle_island(amp_m, o)
    real(dp), intent(in) :: amp_m
    type(run_outcome_t), intent(out) :: o
    o%amplitude_m = amp_m
    o%collapsed = (amp_m >= 0.0620_dp .and. amp_m < 0.0634_dp) .or. amp_m >= 0.0646_dp
    o%peak_crown_disp_m = merge(0.0_dp, 5.0e-3_dp, amp_m < 0.058_dp)
    o%n_steps = 100
    o%mean_iterations = 10.0_dp
  end subroutine oracle_island

  !> Collapse in [60.5, 62.0) mm and from 63.0 mm; a safe island between.
  subroutine oracle_mid_island(amp_m, o)
    real(dp), intent(in) :: amp_m
    type(run_outcome_t), intent(out) :: o
    o%amplitude_m = amp_m
    o%collapsed = (amp_m >= 0.0605_dp .and. amp_m < 0.0620_dp) .or. amp_m >= 0.0630_dp
    o%peak_crown_disp_m = merge(0.0_dp, 5.0e-3_dp, amp_m < 0.058_dp)
    o%n_steps = 100
    o%mean_iterations = 10.0_dp
  end subroutine oracle_mid_island

  !> Run a search at 1.25 Hz on synthetic outcomes.
  subroutine drive(c, s, oracle, res, amps, n)
    type(config_t), intent(in) :: c
    type(threshold_settings_t), intent(in) :: s
    interface
      subroutine oracle(amp_m, o)
        import :: dp, run_outcome_t
        real(dp), intent(in) :: amp_m
        type(run_outcome_t), intent(out) :: o
      end subroutine oracle
    end interface
    type(threshold_result_t), intent(out) :: res
    real(dp), intent(out) :: amps(:)
    integer, intent(out) :: n
    type(threshold_search_t) :: search
    type(run_outcome_t) :: o
    type(status_t) :: st
    real(dp) :: a
    logical :: done
    n = 0
    amps = 0.0_dp
    call threshold_init(search, c, 1.25_dp, s, st)
    do while (st%ok .and. n < size(amps))
      call threshold_next(search, a, done)
      if (done) exit
      n = n + 1
      amps(n) = a
      call oracle(a, o)
      call threshold_record(search, o, st)
    end do
    call assert_true(st%ok .and. n < size(amps), 'search ends without error: '//trim(st%message))
    res = threshold_result(search)
  end subroutine drive

  subroutine refuse_foreign_outcome(c, s)
    type(config_t), intent(in) :: c
    type(threshold_settings_t), intent(in) :: s
    type(threshold_search_t) :: search
    type(run_outcome_t) :: o
    type(status_t) :: st
    real(dp) :: a
    logical :: done
    call threshold_init(search, c, 1.25_dp, s, st)
    call threshold_next(search, a, done)
    call oracle_monotone(a*1.01_dp, o)
    call threshold_record(search, o, st)
    call assert_true(.not. st%ok, 'an outcome at another amplitude than proposed is refused')
  end subroutine refuse_foreign_outcome

  subroutine real_search()
    type(config_t) :: c
    type(threshold_settings_t) :: s
    type(threshold_result_t) :: res
    type(run_outcome_t), allocatable :: runs(:)
    type(status_t) :: st
    type(assembly_t) :: assembly
    type(model_t) :: model
    type(run_result_t) :: below, at
    c = seed_156()
    c%solver%dt_s = 2.0e-3_dp
    s%amp_tol_m = 1.0e-3_dp
    s%n_confirm = 0
    call find_threshold(c, 2.0_dp, s, res, st, runs)
    call assert_true(st%ok, '156-degree arch at 2 Hz: search runs: '//trim(st%message))
    if (.not. st%ok) return
    write (*, '(a,f0.3,a,i0,a)') '      156-degree arch, 2 Hz: threshold ', 1.0e3_dp*res%threshold_m, &
      ' mm in ', res%n_runs, ' runs'
    call assert_true(res%threshold_m > static_onset_amplitude_m(c, 2.0_dp), &
                     'real search: threshold above the static onset')
    call assert_true(size(runs) == res%n_runs, 'real search: every run returned')
    call run_config(search_run_config(c, 2.0_dp, res%threshold_m - s%amp_tol_m), assembly, model, below, st)
    call assert_true(st%ok .and. .not. below%collapsed, 'real search: a single run at threshold - amp_tol stands')
    call run_config(search_run_config(c, 2.0_dp, res%threshold_m), assembly, model, at, st)
    call assert_true(st%ok .and. at%collapsed, 'real search: a single run at the threshold collapses')
  end subroutine real_search

end program test_threshold
