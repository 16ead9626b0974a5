!> voussoir-limit FILE.nml [--json]: limit analysis of the assembly that FILE.nml describes
!> (the arch builder, a &wall or a polygon file, as voussoir-run reads them). For an arch:
!> horizontal collapse multipliers towards +x and -x with their four-hinge mechanisms, the
!> friction check, and the minimum thickness of the arch with its hinges. For every
!> assembly: the load factor by linear programming, associative and non-associative,
!> with mechanisms and contact forces. Prints a table, or with --json exactly
!> one JSON object on stdout (docs/results_format.md, "voussoir-limit --json").
!> The optional &limit group is documented in docs/limit_analysis.md. Errors go to
!> stderr with a non-zero exit code.
program voussoir_limit
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use voussoir_status, only: status_t
  use voussoir_config, only: config_t, read_config, config_groups
  use voussoir_wall_config, only: wall_group
  use voussoir_load_config, only: load_group
  use voussoir_bridge_config, only: bridge_group
  use voussoir_vehicle_config, only: vehicle_group
  use voussoir_namelist_group, only: nml_group_t
  use voussoir_assembly, only: assembly_t
  use voussoir_limit_analysis, only: limit_result_t
  use voussoir_limit_study, only: limit_options_t, thickness_result_t, read_limit_group, analyse, limit_table
  use voussoir_limit_lp_study, only: lp_study_t
  use voussoir_limit_load_cases, only: case_study_t
  use voussoir_load_case_config, only: load_cases_group
  use voussoir_limit_output, only: write_table, write_json
  use voussoir_command_line, only: input_argument, write_warnings
  implicit none

  type(config_t) :: cfg
  type(limit_options_t) :: opts
  type(assembly_t) :: arch
  type(limit_result_t) :: res
  type(thickness_result_t) :: tmin
  type(lp_study_t) :: lp
  type(case_study_t), allocatable :: cases(:)
  type(status_t) :: status
  character(len=1024) :: path
  logical :: json

  call parse_arguments(path, json)
  call read_config(trim(path), [character(len=10) :: 'arch', 'wall', 'motion', 'solver', 'output', 'limit', 'load', &
                   'bridge', 'vehicle', 'load_cases'], &
                   cfg, status)
  if (status%ok) call write_warnings('voussoir-limit', cfg%warnings)
  if (status%ok) call read_limit_group(trim(path), cfg, opts, status)
  if (status%ok) call analyse(cfg, opts, arch, res, tmin, lp, cases, status)
  if (.not. status%ok) then
    write (error_unit, '(a)') 'voussoir-limit: error: '//trim(status%message)
    stop 1, quiet=.true.
  end if
  if (json) then
    call write_json(output_unit, trim(path), cfg, opts, arch, res, tmin, lp, cases)
  else
    call write_table(output_unit, trim(path), cfg, opts, res, tmin, lp, cases)
  end if

contains

  !> FILE.nml and the optional --json, in either order.
  subroutine parse_arguments(path, json)
    character(len=*), intent(out) :: path
    logical, intent(out) :: json
    logical :: given(1)
    integer :: exit_code
    type(config_t), target :: defaults          ! what --help lists the tables over
    type(limit_options_t), target :: limit_defaults
    type(nml_group_t) :: tables(10)
    call config_groups(defaults, tables(1:4))
    call wall_group(defaults%wall, tables(5))
    call limit_table(limit_defaults, tables(6))
    call load_group(defaults%load, tables(7))
    call bridge_group(defaults%bridge, tables(8))
    call vehicle_group(defaults%vehicle, tables(9))
    call load_cases_group(defaults%cases, tables(10))
    call input_argument('voussoir-limit', 'voussoir-limit FILE.nml [--json]', &
      'Limit analysis of the assembly of FILE.nml (arch, &wall, &bridge or polygon file): the horizontal acceleration '// &
      '(in g) that brings it down statically, by linear programming with Coulomb friction (associative and '// &
      'non-associative) and, for an arch, by its four-hinge mechanism, with optionally the minimum thickness '// &
      '(&limit; docs/limit_analysis.md). --json prints the result as JSON. It reads the groups of voussoir-run '// &
      'and &limit, listed below.', path, exit_code, ['--json'], &
      given, tables)
    if (exit_code >= 0) stop exit_code, quiet=.true.
    json = given(1)
  end subroutine parse_arguments

end program voussoir_limit
