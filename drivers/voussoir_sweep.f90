!> voussoir-sweep FILE.nml: many simulations of one base case, spread over MPI ranks.
!>
!> `mpirun -np N voussoir-sweep FILE.nml`. The &arch (or &bridge, with &load and &vehicle),
!> &motion, &solver and &output groups give the base case as for voussoir-run; &sweep
!> says what varies (docs/sweep.md):
!> mode 'threshold' finds the collapse threshold amplitude at each frequency, mode 'grid'
!> runs every frequency x amplitude; optional lists over model parameters make parameter
!> sets (Cartesian product or paired). Rank 0 writes &output's `file` (HDF5, always
!> whole) and a CSV summary beside it, and resumes from that file when rerun.
!>
!> The sweep plan and its mode (no MPI) are src/sweep/ (sweep_plan.f90, sweep_mode*.f90);
!> the MPI layer drivers/sweep/sweep_comm.f90; the master and the workers
!> drivers/sweep/sweep_master.f90 and sweep_worker.f90, the tasks between them
!> drivers/sweep/sweep_tasks.f90.

!> The program: read the input on every rank, let rank 0 check the result file, then
!> master and workers.
program voussoir_sweep
  use, intrinsic :: iso_fortran_env, only: output_unit
  use voussoir_status, only: status_t
  use voussoir_config, only: config_t, read_config, config_groups
  use voussoir_load_config, only: load_group
  use voussoir_bridge_config, only: bridge_group
  use voussoir_vehicle_config, only: vehicle_group
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_sweep_group, only: sweep_group_t, sweep_table
  use voussoir_sweep_mode_factory, only: default_mode
  use voussoir_sweep_plan, only: sweep_plan_t, read_sweep_plan
  use voussoir_sweep_comm, only: sweep_comm_t, comm_start, comm_end, comm_agree
  use voussoir_sweep_master, only: master_t, master_prepare, master_run
  use voussoir_sweep_worker, only: worker_run
  use voussoir_command_line, only: input_argument, write_warnings
  use voussoir_sweep_row_inputs, only: write_row_inputs, row_input_stem
  use voussoir_text, only: itoa
  implicit none
  type(sweep_comm_t) :: net
  type(config_t) :: cfg
  type(config_t), target :: defaults          ! what --help lists the tables over
  type(sweep_group_t), target :: sweep_defaults
  type(nml_group_t) :: tables(8)
  type(sweep_plan_t) :: plan
  type(master_t) :: master
  type(status_t) :: status
  character(len=1024) :: path
  integer :: exit_code, n_written
  logical :: write_rows(1)

  call config_groups(defaults, tables(1:4))
  sweep_defaults%mode = default_mode
  call sweep_table(sweep_defaults, tables(5))
  call load_group(defaults%load, tables(6))
  call bridge_group(defaults%bridge, tables(7))
  call vehicle_group(defaults%vehicle, tables(8))
  call input_argument('voussoir-sweep', 'mpirun -np N voussoir-sweep FILE.nml [--write-rows]', &
    'A sweep of simulations over MPI ranks (rank 0 schedules, the others run): collapse envelopes over '// &
    'frequencies and amplitudes, threshold searches, lists of arch parameters, or an incremental dynamic '// &
    'analysis under records (&sweep mode; docs/sweep.md, docs/earthquakes.md). Writes an HDF5 file and a CSV '// &
    'beside it, updated as jobs finish; a rerun continues a killed sweep. The groups &arch, &motion, &solver '// &
    'and &output give the base case as for voussoir-run (or &bridge instead of &arch, with &load and &vehicle as '// &
    'voussoir-run takes them: docs/bridges.md), &sweep what varies (its ranges depend on the mode: '// &
    'docs/sweep.md). --write-rows: once the sweep is done (or found complete), an input of voussoir-run for each '// &
    'run behind each row beside the result (an IDA row: its runs at scale_stood and scale_threshold), '// &
    '<file stem>_job<J>_<stood|collapsed|run|threshold>.nml: voussoir-run on it replays the run as the sweep '// &
    'ran it (docs/sweep.md).', path, exit_code, flags=['--write-rows'], given=write_rows, groups=tables)
  if (exit_code >= 0) stop exit_code, quiet=.true.
  call comm_start(net)
  call read_config(trim(path), [character(len=8) :: 'arch', 'motion', 'solver', 'output', 'sweep', 'load', &
                   'bridge', 'vehicle'], cfg, status)
  if (status%ok .and. net%rank == 0) call write_warnings('voussoir-sweep', cfg%warnings)
  if (status%ok) call read_sweep_plan(trim(path), cfg, plan, status)
  if (status%ok .and. net%rank == 0) call master_prepare(plan, cfg, net%size, master, status)
  ! Every rank read the same input; only rank 0 knows whether the result file is usable.
  if (.not. comm_agree(net, status%ok)) then
    if (net%rank == 0) write (output_unit, '(a)') 'voussoir-sweep: error: '//trim(status%message)
    call comm_end(net)
    ! Every rank stops with code 1; quietly, since error stop would print a backtrace per rank.
    stop 1, quiet=.true.
  end if
  if (net%rank == 0) then
    call master_run(plan, net, master)
    if (write_rows(1)) call write_row_inputs(plan, master%results, master%runs, master%path, n_written, status)
    if (write_rows(1) .and. status%ok) write (output_unit, '(a)') 'voussoir-sweep: wrote '//itoa(n_written)// &
      ' inputs of voussoir-run, the runs behind the rows: '//row_input_stem(master%path)//'_job<J>_<run>.nml'
  else
    call worker_run(plan, net)
  end if
  call comm_end(net)
  if (.not. status%ok) then
    write (output_unit, '(a)') 'voussoir-sweep: error: '//trim(status%message)
    stop 1, quiet=.true.
  end if
end program voussoir_sweep
