!> A sweep mode as a type: what the &sweep `mode` makes of a plan. The abstract
!> `sweep_mode_t` says what every mode provides (its settings read and checked, its jobs,
!> the run of one job, its search, its result columns, file items, CSV and labels); one
!> file per mode extends it (src/sweep/sweep_mode_*.f90) and the factory
!> (src/sweep/sweep_mode_factory.f90) makes one from its name. The plan carries its mode,
!> so that the MPI master and workers and the result file call the mode and never ask
!> which one it is.
!>
!> A job is "runs proposed one at a time until done": a single run (`has_search` false:
!> its value is `run_value`), or a threshold search (`search_init`, then the state
!> machine of src/sweep/threshold_search.f90, which any rank can continue from its
!> history).
module voussoir_sweep_mode
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: fmt_real
  use voussoir_config, only: config_t
  use voussoir_threshold_search, only: threshold_settings_t, threshold_search_t, threshold_result_t, run_outcome_t
  use voussoir_sweep_ida, only: ida_records_t
  use voussoir_sweep_group, only: sweep_group_t
  use voussoir_sweep_table, only: sweep_table_t, named_values_t, named_text_t, runs_table, table_value
  implicit none
  private

  public :: sweep_mode_t, sweep_plan_t, job_param_set, set_description, run_bodies

  !> What every sweep mode provides. `plan` is the plan that carries the mode.
  type, abstract :: sweep_mode_t
    character(len=16) :: name = ''   !! as in &sweep mode; the factory sets it
  contains
    ! Reading the plan.
    procedure(check_settings_i), deferred :: check_settings
    procedure :: draw_sets
    procedure :: prepare_sets
    procedure(plan_text_i), deferred :: settings_text
    procedure :: definition_text
    ! The jobs.
    procedure(plan_text_i), deferred :: jobs_text
    procedure(job_text_i), deferred :: job_label
    procedure(run_config_i), deferred :: run_config
    procedure(job_real_i), deferred :: cost
    procedure :: frequency_hz
    procedure :: run_value
    procedure :: has_search
    procedure :: search_init
    procedure :: value_name
    ! The results.
    procedure(results_table_i), deferred :: results_table
    procedure :: runs_table => mode_runs_table
    procedure(result_row_i), deferred :: result_row
    procedure(file_items_i), deferred :: file_items
    procedure(csv_header_i), deferred :: csv_header
    procedure(csv_line_i), deferred :: csv_line
    procedure(row_text_i), deferred :: summary_line
    procedure :: closing_check
    procedure :: row_runs
    ! The assembly.
    procedure :: bridge_refusal
  end type sweep_mode_t

  !> Everything a rank needs to turn a job index into a run.
  type :: sweep_plan_t
    class(sweep_mode_t), allocatable :: mode      !! threshold, grid or ida (the factory)
    character(len=16) :: combine = 'product'      !! product or paired
    logical :: pair_frequencies = .false.         !! frequency k goes with parameter set k only
    real(dp), allocatable :: frequencies_hz(:)
    type(threshold_settings_t) :: search          !! threshold and ida modes (ida: over the scale)
    type(ida_records_t) :: records                !! ida mode
    real(dp) :: progress_every_s = 10.0_dp        !! seconds between progress lines
    !> The plan's cost, estimated before it starts (sweep_plan.f90): runs (a search counted
    !> at its typical runs), simulated seconds, and steps x blocks summed over the runs.
    real(dp) :: est_runs = 0.0_dp, est_simulated_s = 0.0_dp, est_step_blocks = 0.0_dp
    integer :: n_params = 0, n_sets = 1, n_freq = 0, n_amp = 1, n_jobs = 0
    integer :: n_freq_per_set = 0                 !! n_freq, or 1 with pair_frequencies; ida: the records
    character(len=24), allocatable :: param_names(:)
    real(dp), allocatable :: param_values(:, :)   !! (n_params, n_sets)
    type(config_t), allocatable :: set_cfg(:)     !! (0:n_sets-1) the validated case of each set
    character(len=:), allocatable :: sweep_nml    !! the effective &sweep group
    character(len=:), allocatable :: signature    !! what a resumed file must match
    character(len=:), allocatable :: note         !! a line for the log from reading the plan ('' or unset: none)
    !> The `# code:` line of the model samples file (the code that wrote it; '' or unset: none)
    character(len=:), allocatable :: samples_code
  end type sweep_plan_t

  abstract interface
    !> Check the mode's &sweep variables in `group` against the base case and set the
    !> plan's frequencies, job layout (n_freq_per_set, n_amp) and search; an error names
    !> the file `path`, the variable and the allowed range.
    subroutine check_settings_i(this, group, base, path, plan, status)
      import :: sweep_mode_t, sweep_group_t, config_t, sweep_plan_t, status_t
      class(sweep_mode_t), intent(inout) :: this
      type(sweep_group_t), intent(in) :: group
      type(config_t), intent(in) :: base
      character(len=*), intent(in) :: path
      type(sweep_plan_t), intent(inout) :: plan
      type(status_t), intent(inout) :: status
    end subroutine check_settings_i
    !> A text of the plan (the mode's lines of the effective &sweep group; the jobs in
    !> words for the log).
    function plan_text_i(this, plan) result(text)
      import :: sweep_mode_t, sweep_plan_t
      class(sweep_mode_t), intent(in) :: this
      type(sweep_plan_t), intent(in) :: plan
      character(len=:), allocatable :: text
    end function plan_text_i
    !> A text of job `job` (0-based): what it runs beside its parameter set.
    function job_text_i(this, plan, job) result(text)
      import :: sweep_mode_t, sweep_plan_t
      class(sweep_mode_t), intent(in) :: this
      type(sweep_plan_t), intent(in) :: plan
      integer, intent(in) :: job
      character(len=:), allocatable :: text
    end function job_text_i
    !> The configuration of one run of job `job` at `value` (an amplitude, a scale).
    pure function run_config_i(this, plan, job, value) result(cfg)
      import :: sweep_mode_t, sweep_plan_t, config_t, dp
      class(sweep_mode_t), intent(in) :: this
      type(sweep_plan_t), intent(in) :: plan
      integer, intent(in) :: job
      real(dp), intent(in) :: value
      type(config_t) :: cfg
    end function run_config_i
    !> A number of job `job` (the relative cost of one of its runs).
    pure real(dp) function job_real_i(this, plan, job)
      import :: sweep_mode_t, sweep_plan_t, dp
      class(sweep_mode_t), intent(in) :: this
      type(sweep_plan_t), intent(in) :: plan
      integer, intent(in) :: job
    end function job_real_i
    !> An empty /results table with the mode's columns.
    function results_table_i(this) result(t)
      import :: sweep_mode_t, sweep_table_t
      class(sweep_mode_t), intent(in) :: this
      type(sweep_table_t) :: t
    end function results_table_i
    !> Fill `row` (a row of `results`, its `failed` column set) for the finished job
    !> `job`: from the outcome `o` of its single run, or from the result `r` of its search
    !> (`failed`: ended by a run that failed).
    subroutine result_row_i(this, plan, job, o, r, failed, results, row)
      import :: sweep_mode_t, sweep_plan_t, run_outcome_t, threshold_result_t, sweep_table_t, dp
      class(sweep_mode_t), intent(in) :: this
      type(sweep_plan_t), intent(in) :: plan
      integer, intent(in) :: job
      type(run_outcome_t), intent(in) :: o
      type(threshold_result_t), intent(in) :: r
      logical, intent(in) :: failed
      type(sweep_table_t), intent(in) :: results
      real(dp), intent(inout) :: row(:)
    end subroutine result_row_i
    !> What the result file keeps of the mode besides its tables: datasets under /sweep
    !> and attributes of the file.
    subroutine file_items_i(this, plan, datasets, attributes)
      import :: sweep_mode_t, sweep_plan_t, named_values_t, named_text_t
      class(sweep_mode_t), intent(in) :: this
      type(sweep_plan_t), intent(in) :: plan
      type(named_values_t), allocatable, intent(out) :: datasets(:)
      type(named_text_t), allocatable, intent(out) :: attributes(:)
    end subroutine file_items_i
    !> The header line of the CSV summary; `names` is ",<parameter names>" or empty.
    function csv_header_i(this, names) result(text)
      import :: sweep_mode_t
      class(sweep_mode_t), intent(in) :: this
      character(len=*), intent(in) :: names
      character(len=:), allocatable :: text
    end function csv_header_i
    !> The CSV line of row `r` of `results`; `set_columns` is "<param_set>,<its values>".
    function csv_line_i(this, plan, results, r, set_columns) result(line)
      import :: sweep_mode_t, sweep_plan_t, sweep_table_t
      class(sweep_mode_t), intent(in) :: this
      type(sweep_plan_t), intent(in) :: plan
      type(sweep_table_t), intent(in) :: results
      integer, intent(in) :: r
      character(len=*), intent(in) :: set_columns
      character(len=:), allocatable :: line
    end function csv_line_i
    !> A text of row `r` of `results` (the line of the closing summary; empty: none).
    function row_text_i(this, plan, results, r) result(line)
      import :: sweep_mode_t, sweep_plan_t, sweep_table_t
      class(sweep_mode_t), intent(in) :: this
      type(sweep_plan_t), intent(in) :: plan
      type(sweep_table_t), intent(in) :: results
      integer, intent(in) :: r
      character(len=:), allocatable :: line
    end function row_text_i
  end interface

contains

  !> Parameter set (0-based) of job `job` (0-based).
  pure integer function job_param_set(plan, job)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    job_param_set = job/(plan%n_freq_per_set*plan%n_amp)
  end function job_param_set

  !> "name = value, ..." of parameter set `s` (0-based), or "base case".
  function set_description(plan, s) result(text)
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: s
    character(len=:), allocatable :: text
    integer :: p
    text = ''
    do p = 1, plan%n_params
      if (p > 1) text = text//', '
      text = text//trim(plan%param_names(p))//' = '//fmt_real(plan%param_values(p, s + 1))
    end do
    if (plan%n_params == 0) text = 'base case'
  end function set_description

  !> Draw the parameter sets instead of taking them from the lists (`drawn`); a mode
  !> that samples its models overrides it. `lengths`: the lists given.
  subroutine draw_sets(this, group, base, path, lengths, plan, drawn, status)
    class(sweep_mode_t), intent(in) :: this
    type(sweep_group_t), intent(in) :: group
    type(config_t), intent(in) :: base
    character(len=*), intent(in) :: path
    integer, intent(in) :: lengths(:)
    type(sweep_plan_t), intent(inout) :: plan
    logical, intent(out) :: drawn
    type(status_t), intent(inout) :: status
    drawn = .false.
  end subroutine draw_sets

  !> What the mode adds to the validated case of each set once the sets are made (nothing
  !> here).
  subroutine prepare_sets(this, group, plan, status)
    class(sweep_mode_t), intent(inout) :: this
    type(sweep_group_t), intent(in) :: group
    type(sweep_plan_t), intent(inout) :: plan
    type(status_t), intent(inout) :: status
  end subroutine prepare_sets

  !> Lines of the sweep definition (the signature a resumed file must match) besides the
  !> effective &sweep group and the base case: what a file the mode reads gave (none here).
  function definition_text(this, plan) result(text)
    class(sweep_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    character(len=:), allocatable :: text
    text = ''
  end function definition_text

  !> The table frequency of job `job` [Hz] (0 when the mode has none).
  pure real(dp) function frequency_hz(this, plan, job)
    class(sweep_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    frequency_hz = 0.0_dp
  end function frequency_hz

  !> The value (amplitude) of the single run of job `job`; 0 when its runs come from a
  !> search.
  pure real(dp) function run_value(this, plan, job)
    class(sweep_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    run_value = 0.0_dp
  end function run_value

  !> Whether a job is a search (else one run at `run_value`).
  pure logical function has_search(this)
    class(sweep_mode_t), intent(in) :: this
    has_search = .false.
  end function has_search

  !> A new search for job `job` (modes whose jobs are searches override it).
  subroutine search_init(this, plan, job, search, status)
    class(sweep_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    integer, intent(in) :: job
    type(threshold_search_t), intent(out) :: search
    type(status_t), intent(inout) :: status
    call fail(status, "internal: a job of mode '"//trim(this%name)//"' is not a search")
  end subroutine search_init

  !> The name of the variable a job's runs vary, a column of /runs.
  pure function value_name(this) result(name)
    class(sweep_mode_t), intent(in) :: this
    character(len=:), allocatable :: name
    name = 'amplitude_m'
  end function value_name

  !> An empty /runs table: every run of the searches (none when jobs are single runs).
  function mode_runs_table(this) result(t)
    class(sweep_mode_t), intent(in) :: this
    type(sweep_table_t) :: t
    if (this%has_search()) t = runs_table(this%value_name())
  end function mode_runs_table

  !> A check after the jobs (rank 0): `extra` a table for the file (left without
  !> columns when there is none), `report` a line for the log (empty: none).
  subroutine closing_check(this, plan, results, extra, report, status)
    class(sweep_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    type(sweep_table_t), intent(out) :: extra
    character(len=:), allocatable, intent(out) :: report
    type(status_t), intent(inout) :: status
    report = ''
  end subroutine closing_check

  !> The runs behind row `r` of `results` (`voussoir-sweep --write-rows` writes each as an
  !> input of voussoir-run): their values and a word each for the file name. Here a
  !> single run's value ('run'), and none for a search: a mode whose jobs are searches
  !> overrides it with the runs of its row's bracket.
  subroutine row_runs(this, plan, results, r, values, words)
    class(sweep_mode_t), intent(in) :: this
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    integer, intent(in) :: r
    real(dp), allocatable, intent(out) :: values(:)
    character(len=16), allocatable, intent(out) :: words(:)
    allocate (values(0), words(0))
    if (this%has_search()) return
    values = [this%run_value(plan, nint(table_value(results, 'job', r)))]
    words = [character(len=16) :: 'run']
  end subroutine row_runs

  !> Why the mode cannot sweep a &bridge, or '' when it can (here: it can).
  function bridge_refusal(this) result(why)
    class(sweep_mode_t), intent(in) :: this
    character(len=:), allocatable :: why
    why = ''
  end function bridge_refusal

  !> The bodies of a run of `cfg`, the unit of a run's cost (steps x bodies): a bridge's
  !> blocks (its voussoirs, piers, abutments and ground: src/assembly/bridge.f90), else
  !> the arch's voussoirs and its two supports.
  pure integer function run_bodies(cfg)
    type(config_t), intent(in) :: cfg
    associate (b => cfg%bridge)
      if (b%n_spans > 0) then
        run_bodies = b%n_spans*b%n_voussoirs + (b%n_spans - 1) + 2 + merge(1, 0, b%n_spans > 1)
      else
        run_bodies = cfg%arch%n_voussoirs + 2
      end if
    end associate
  end function run_bodies

end module voussoir_sweep_mode
