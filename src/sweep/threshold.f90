!> The runs of a threshold search (the state machine itself is
!> src/sweep/threshold_search.f90): the configuration of one search run and its outcome,
!> the static onset that starts a search (limit analysis), and `find_threshold`, the
!> whole search in this process. docs/sweep.md explains the search.
module voussoir_threshold
  use voussoir_kinds, only: dp, g_m_s2
  use voussoir_status, only: status_t, fail
  use voussoir_config, only: config_t, fmt_real, waveform_afd, springings_none, has_loads
  use voussoir_assembly, only: assembly_t, build_arch, voussoir_angle_factors
  use voussoir_config_assembly, only: build_config_assembly
  use voussoir_limit_analysis, only: limit_result_t, horizontal_capacity
  use voussoir_limit_lp_study, only: lp_study_t, lp_study
  use voussoir_limit_lp, only: lp_result_t
  use voussoir_motion, only: motion_t, motion_afd, motion_eval, motion_duration_s
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: run_config
  use voussoir_threshold_search, only: threshold_settings_t, run_outcome_t, threshold_search_t, threshold_result_t, &
                                       check_threshold_settings, threshold_init_onset, threshold_next, &
                                       threshold_record, threshold_result
  implicit none
  private

  public :: threshold_init, find_threshold, search_run_config, outcome_of_run
  public :: static_onset_amplitude_m, afd_peak_accel_per_m, static_capacity_m_s2

  !> Samples per cycle when the peak acceleration of the afd waveform is measured.
  integer, parameter :: samples_per_cycle = 2000
  !> Output interval of a search run [steps]: no time series is needed.
  integer, parameter :: no_samples = huge(1)

contains

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
    outcome%peak_joint_opening_m = res%peak_joint_opening_m
    outcome%residual_crown_drift_m = res%residual_crown_drift_m
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
  !> move. 0 when there is no capacity (the LP has no answer).
  real(dp) function static_onset_amplitude_m(cfg, frequency_hz) result(amp_m)
    type(config_t), intent(in) :: cfg
    real(dp), intent(in) :: frequency_hz
    amp_m = static_capacity_m_s2(cfg)
    if (amp_m > 0.0_dp) amp_m = amp_m/afd_peak_accel_per_m(cfg, frequency_hz)
  end function static_onset_amplitude_m

  !> The horizontal collapse capacity lambda g [m/s2] of the arch of `cfg` (limit
  !> analysis, the weaker direction); 0 when there is none (the LP has no answer, a polygon
  !> file cannot be read). Where the four-hinge mechanism's static field breaks Coulomb's law at a
  !> joint (`&arch friction`), sliding may govern: the capacity is then the lesser of the
  !> four-hinge one and the non-associative LP capacity (the joints slide without
  !> dilating) in that direction (docs/limit_analysis.md). With the loads of &load, the
  !> LP's capacity with them (`loaded_capacity`); a &bridge, a &wall, a polygon file or an
  !> arch with restraint brackets, which the four-hinge analysis does not model, has the
  !> LP's alone (a polygon file's driven blocks are its fixed supports; a bridge's fill as
  !> the run has it, mass its voussoirs carry).
  real(dp) function static_capacity_m_s2(cfg) result(capacity)
    type(config_t), intent(in) :: cfg
    type(assembly_t) :: arch
    type(limit_result_t) :: limit
    type(status_t) :: status
    real(dp) :: lambda

    capacity = 0.0_dp
    if (cfg%bridge%n_spans > 0 .or. cfg%wall%courses > 0 .or. len_trim(cfg%arch%polygon_file) > 0 .or. &
        cfg%arch%restrained_springings /= springings_none) then
      call build_config_assembly(cfg, arch, status)
      if (status%ok) capacity = loaded_capacity(arch, cfg)
      return
    end if
    if (cfg%arch%n_voussoirs < 3) return
    call build_arch(cfg%arch%embrace_deg, cfg%arch%n_voussoirs, cfg%arch%r_ext_m, cfg%arch%thickness_m, arch, &
                    angle_factors=voussoir_angle_factors(cfg%arch%n_voussoirs, cfg%arch%size_imperfection, &
                                                         cfg%arch%imperfection_seed))
    if (has_loads(cfg)) then
      capacity = loaded_capacity(arch, cfg)
      return
    end if
    call horizontal_capacity(arch, cfg%arch%contact_inset_m, cfg%arch%friction, limit, status, &
                             cfg%arch%joint_friction)
    if (.not. status%ok) return
    lambda = min(limit%lambda_pos, limit%lambda_neg)
    if (allocated(limit%sliding_joints_pos) .and. allocated(limit%sliding_joints_neg)) then
      if (size(limit%sliding_joints_pos) > 0 .or. size(limit%sliding_joints_neg) > 0) &
        lambda = min(lambda, sliding_capacity(arch, cfg, size(limit%sliding_joints_pos) > 0, &
                                              size(limit%sliding_joints_neg) > 0))
    end if
    if (.not. (lambda > 0.0_dp .and. lambda < huge(1.0_dp))) return
    capacity = lambda*g_m_s2
  end function static_capacity_m_s2

  !> The load factor of a horizontal acceleration of the blocks `asm` with sliding (the
  !> non-associative LP; the associative one if its iteration failed), towards +x where
  !> `pos`, towards -x where `neg`, the lesser of those asked; the joints' friction as in
  !> the dynamics (&arch joint_friction where set). Huge when the LP has no answer (the
  !> four-hinge capacity then stands alone).
  real(dp) function sliding_capacity(asm, cfg, pos, neg) result(lambda)
    type(assembly_t), intent(in) :: asm
    type(config_t), intent(in) :: cfg
    logical, intent(in) :: pos, neg
    type(lp_study_t) :: study
    type(status_t) :: status
    lambda = huge(1.0_dp)
    call lp_study(asm, cfg%arch%density_kg_m3, cfg%arch%width_m, cfg%arch%friction, cfg%arch%contact_inset_m, &
                  study, status, joint_friction=cfg%arch%joint_friction)
    if (.not. study%solved) return
    if (pos) lambda = direction_lambda(study%assoc, study%nonassoc, study%nonassociative_solved)
    if (neg .and. study%neg%solved) lambda = min(lambda, direction_lambda(study%neg%assoc, study%neg%nonassoc, &
                                                                         study%neg%nonassociative_solved))
  end function sliding_capacity

  !> The capacity lambda g [m/s2] of the assembly `asm` loaded by &load (if any) as a run
  !> applies the loads (all dead, at their places; the four-hinge analysis takes the
  !> weights alone): the LP's non-associative load factor of the weaker direction; 0 when
  !> it has none. A bridge's fill as the run has it: mass the blocks carry (accelerated
  !> with them), its horizontal pressure active.
  real(dp) function loaded_capacity(asm, cfg) result(capacity)
    type(assembly_t), intent(in) :: asm
    type(config_t), intent(in) :: cfg
    type(lp_study_t) :: study
    type(status_t) :: status
    real(dp) :: lambda
    capacity = 0.0_dp
    call lp_study(asm, cfg%arch%density_kg_m3, cfg%arch%width_m, cfg%arch%friction, cfg%arch%contact_inset_m, &
                  study, status, load=cfg%load, joint_friction=cfg%arch%joint_friction, loads_dead=.true., &
                  fill_as_mass=.true.)
    if (.not. study%solved) return
    lambda = direction_lambda(study%assoc, study%nonassoc, study%nonassociative_solved)
    if (study%neg%solved) lambda = min(lambda, direction_lambda(study%neg%assoc, study%neg%nonassoc, &
                                                                study%neg%nonassociative_solved))
    if (lambda < huge(1.0_dp)) capacity = lambda*g_m_s2
  end function loaded_capacity

  !> The non-associative load factor where there is one, else the associative; huge
  !> where not positive.
  pure real(dp) function direction_lambda(assoc, nonassoc, nonassociative_solved) result(lambda)
    type(lp_result_t), intent(in) :: assoc, nonassoc
    logical, intent(in) :: nonassociative_solved
    lambda = assoc%load_factor
    if (nonassociative_solved) lambda = nonassoc%load_factor
    if (.not. (lambda > 0.0_dp)) lambda = huge(1.0_dp)
  end function direction_lambda

  !> A new search for the case `cfg` (an afd motion) at `frequency_hz`.
  subroutine threshold_init(search, cfg, frequency_hz, settings, status)
    type(threshold_search_t), intent(out) :: search
    type(config_t), intent(in) :: cfg
    real(dp), intent(in) :: frequency_hz
    type(threshold_settings_t), intent(in) :: settings
    type(status_t), intent(inout) :: status

    call check_threshold_settings(settings, status)
    if (.not. status%ok) return
    if (cfg%motion%waveform /= waveform_afd) then
      call fail(status, "threshold search: &motion waveform = '"//trim(cfg%motion%waveform)// &
                "' has no amplitude to search; it must be '"//waveform_afd//"'")
      return
    end if
    if (.not. (frequency_hz > 0.0_dp)) then
      call fail(status, 'threshold search: frequency_hz = '//fmt_real(frequency_hz)//' must be > 0')
      return
    end if
    call threshold_init_onset(search, cfg, static_onset_amplitude_m(cfg, frequency_hz), settings, status)
    search%frequency_hz = frequency_hz
  end subroutine threshold_init

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
