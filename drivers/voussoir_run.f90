!> voussoir-run FILE.nml: one simulation of an arch (or a polygon assembly) under base
!> motion; writes one HDF5 file and prints a one-line summary whose first word is
!> `stood` or `collapsed`.
program voussoir_run
  use, intrinsic :: iso_fortran_env, only: error_unit
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_config, only: config_t, read_config, config_groups
  use voussoir_wall_config, only: wall_group
  use voussoir_load_config, only: load_group
  use voussoir_bridge_config, only: bridge_group
  use voussoir_vehicle_config, only: vehicle_group
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_assembly, only: assembly_t
  use voussoir_model, only: model_t
  use voussoir_simulation, only: run_result_t
  use voussoir_setup, only: run_config
  use voussoir_run_output, only: write_run_file
  use voussoir_command_line, only: input_argument, write_warnings
  use voussoir_interrupt, only: catch_stop_signals
  use voussoir_text, only: fmt_fixed, itoa
  implicit none
  type(config_t) :: cfg
  type(config_t), target :: defaults          ! what --help lists the tables over
  type(nml_group_t) :: tables(8)
  type(assembly_t) :: assembly
  type(model_t) :: model
  type(run_result_t) :: res
  type(status_t) :: status
  character(len=1024) :: path
  integer :: exit_code

  call config_groups(defaults, tables(1:4))
  call wall_group(defaults%wall, tables(5))
  call load_group(defaults%load, tables(6))
  call bridge_group(defaults%bridge, tables(7))
  call vehicle_group(defaults%vehicle, tables(8))
  call input_argument('voussoir-run', 'voussoir-run FILE.nml', &
    'One simulation of a masonry arch (or a polygon assembly) under base motion: the groups &arch, '// &
    '&motion, &solver and &output of FILE.nml, and &wall, &bridge or &load where given (listed below; README.md and '// &
    'docs/ explain them). Writes one HDF5 result file and prints one line whose first word is stood or '// &
    'collapsed. Exit 0 on success, 1 with a one-line message naming the file, the variable and the allowed '// &
    'range.', path, exit_code, groups=tables)
  if (exit_code >= 0) stop exit_code, quiet=.true.
  call read_config(trim(path), [character(len=8) :: 'arch', 'motion', 'solver', 'output', 'wall', 'load', 'bridge', &
                   'vehicle'], &
                   cfg, status)
  if (status%ok) call write_warnings('voussoir-run', cfg%warnings)
  if (status%ok .and. .not. catch_stop_signals()) &
    write (error_unit, '(a)') 'voussoir-run: warning: cannot catch Ctrl-C / SIGTERM: an interrupted run writes nothing'
  if (status%ok) call run_config(cfg, assembly, model, res, status, record_contacts=.true.)
  if (status%ok) call write_run_file(cfg, assembly, model, res, status)
  if (.not. status%ok) then
    write (error_unit, '(a)') 'voussoir-run: error: '//trim(status%message)
    stop 1, quiet=.true.
  end if
  if (res%interrupted_by /= 0) then
    ! fmt_fixed, not f0.d: '0.018', never '.018'
    write (*, '(a)') 'interrupted at t = '//fmt_fixed(res%time_s(size(res%time_s)), 3)//' s by signal '// &
      itoa(res%interrupted_by)//': the result holds the run until then (/result interrupted_by_signal), '// &
      trim(merge('collapsed so far', 'stood so far    ', res%collapsed))//'; result '//trim(cfg%output%file)
    stop 128 + res%interrupted_by, quiet=.true.
  end if
  if (res%collapsed) then
    write (*, '(a)', advance='no') 'collapsed at '//fmt_fixed(res%collapse_time_s, 3)//' s;'
  else
    write (*, '(a)', advance='no') 'stood;'
  end if
  write (*, '(a)') ' peak crown displacement '//fmt_fixed(1.0e3_dp*res%peak_crown_disp_m, 3)// &
    ' mm; largest final block displacement '//fmt_fixed(1.0e3_dp*res%max_residual_disp_m, 3)//' mm (body '// &
    itoa(res%max_residual_body)//'); mean NLGS iterations '//fmt_fixed(res%mean_iterations, 1)//'; wall time '// &
    fmt_fixed(res%wall_time_s, 2)//' s; result '//trim(cfg%output%file)
  if (res%nonconverged_steps > 0) write (*, '(a,i0,a)') 'warning: ', res%nonconverged_steps, &
    ' steps ended without NLGS convergence'
end program voussoir_run
