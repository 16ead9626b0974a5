!> The inputs of voussoir-run that replay a sweep's rows (`voussoir-sweep --write-rows`):
!> for each row of the results, the runs behind it (the mode's `row_runs`: an IDA row's
!> runs at scale_stood and scale_threshold, a single run's row its run), each as the
!> namelist of the exact configuration the sweep ran (the model sample, the record, its
!> scale and polarity, the solver with the steps at rest, written by `config_to_nml`
!> from the run's `config_t`, the one writer of effective settings), with the base
!> case's &output so that the run keeps its time series. Files beside the sweep's
!> result: `<stem>_job<J>_<stood|collapsed|run|threshold>.nml`.
module voussoir_sweep_row_inputs
  use, intrinsic :: iso_c_binding, only: c_char, c_size_t, c_ptr, c_associated, c_null_char
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, fmt_exact, fmt_fixed
  use voussoir_version, only: code_version
  use voussoir_config, only: config_t, config_entry_t, config_entries, config_to_nml
  use voussoir_sweep_table, only: sweep_table_t, table_value, column_index
  use voussoir_sweep_mode, only: sweep_plan_t, job_param_set, set_description
  implicit none
  private

  public :: write_row_inputs, row_input_stem

  interface
    function c_getcwd(buf, size) bind(C, name='getcwd') result(p)
      import :: c_char, c_size_t, c_ptr
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_size_t), value :: size
      type(c_ptr) :: p
    end function c_getcwd
  end interface

contains

  !> `path` without its `.h5`: the stem of the row inputs' names.
  pure function row_input_stem(path) result(stem)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: stem
    stem = trim(path)
    if (len(stem) > 3) then
      if (stem(len(stem) - 2:) == '.h5') stem = stem(:len(stem) - 3)
    end if
  end function row_input_stem

  !> Write the inputs of every row of `results` (`runs`: the searches' runs, for the
  !> outcome each had in the sweep; empty when jobs are single runs) beside `path`, the
  !> sweep's result file; `n_written` files.
  subroutine write_row_inputs(plan, results, runs, path, n_written, status)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results, runs
    character(len=*), intent(in) :: path
    integer, intent(out) :: n_written
    type(status_t), intent(inout) :: status
    real(dp), allocatable :: values(:)
    character(len=16), allocatable :: words(:)
    character(len=:), allocatable :: stem, name, cwd
    integer :: r, k, job

    n_written = 0
    stem = row_input_stem(path)
    cwd = working_folder()
    do r = 1, results%n_rows
      job = nint(table_value(results, 'job', r))
      call plan%mode%row_runs(plan, results, r, values, words)
      do k = 1, size(values)
        name = stem//'_job'//itoa(job)//'_'//trim(words(k))
        call write_one(plan, runs, job, values(k), name, path, cwd, status)
        if (.not. status%ok) return
        n_written = n_written + 1
      end do
    end do
  end subroutine write_row_inputs

  !> The input `name`.nml of job `job`'s run at `value`.
  subroutine write_one(plan, runs, job, value, name, path, cwd, status)
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: runs
    integer, intent(in) :: job
    real(dp), intent(in) :: value
    character(len=*), intent(in) :: name, path, cwd
    type(status_t), intent(inout) :: status
    type(config_t) :: cfg
    type(config_entry_t), allocatable :: e(:)
    character(len=:), allocatable :: text
    character(len=512) :: msg
    integer :: unit, ios

    cfg = plan%mode%run_config(plan, job, value)
    ! The base case's output (samples, the time after a collapse): a search run keeps none;
    ! neither changes the dynamics, so the outcome and the collapse time are the sweep's.
    cfg%output = plan%set_cfg(job_param_set(plan, job))%output
    cfg%output%file = base_name(name)//'.h5'
    cfg%motion%record_file = absolute(cfg%motion%record_file, cwd)
    cfg%motion%record_vertical_file = absolute(cfg%motion%record_vertical_file, cwd)
    cfg%arch%polygon_file = absolute(cfg%arch%polygon_file, cwd)
    e = config_entries(cfg)
    ! A bridge's &arch holds its ring's values, read from &bridge; voussoir-run takes one of the two.
    if (cfg%bridge%n_spans > 0) e = pack(e, e%group /= 'arch')
    text = '! The run behind job '//itoa(job)//' of '//path//' (its row of /results; '// &
           plan%mode%job_label(plan, job)//'; '//set_description(plan, job_param_set(plan, job))//'):'// &
           achar(10)//'! '//plan%mode%value_name()//' = '//fmt_exact(value)//', '// &
           sweep_outcome(runs, job, value, plan%mode%value_name())//'.'//achar(10)// &
           '! Written by voussoir-sweep --write-rows ('//code_version//'); replay: voussoir-run '// &
           base_name(name)//'.nml'//achar(10)//config_to_nml(e)
    open (newunit=unit, file=name//'.nml', status='replace', action='write', iostat=ios, iomsg=msg)
    if (ios == 0) write (unit, '(a)', iostat=ios, iomsg=msg) text
    if (ios == 0) close (unit, iostat=ios, iomsg=msg)
    if (ios /= 0) call fail(status, name//'.nml: cannot write the input of a row: '//trim(msg))
  end subroutine write_one

  !> What the run of job `job` at `value` gave in the sweep, from `runs`.
  function sweep_outcome(runs, job, value, value_name) result(text)
    type(sweep_table_t), intent(in) :: runs
    integer, intent(in) :: job
    real(dp), intent(in) :: value
    character(len=*), intent(in) :: value_name
    character(len=:), allocatable :: text
    integer :: r
    text = 'a single run of the sweep (its row of /results holds the outcome)'
    if (runs%n_rows == 0) return
    if (column_index(runs, value_name) == 0) return
    text = 'not among the runs of the search (/runs): known from the static capacity'
    do r = 1, runs%n_rows
      if (nint(table_value(runs, 'job', r)) /= job .or. table_value(runs, value_name, r) /= value) cycle
      if (nint(table_value(runs, 'failed', r)) == 1) then
        text = 'which failed in the sweep (run '//itoa(nint(table_value(runs, 'run', r)))//' of /runs)'
      else if (nint(table_value(runs, 'collapsed', r)) == 1) then
        text = 'which collapsed at t = '//fmt_fixed(table_value(runs, 'collapse_time_s', r), 4)// &
               ' s in the sweep (run '//itoa(nint(table_value(runs, 'run', r)))//' of /runs)'
      else
        text = 'which stood in the sweep (run '//itoa(nint(table_value(runs, 'run', r)))//' of /runs)'
      end if
      return
    end do
  end function sweep_outcome

  !> `file` with the folder `cwd` in front when it is relative ('' stays ''; as given
  !> when the whole path would not fit the configuration's text).
  pure function absolute(file, cwd) result(full)
    character(len=*), intent(in) :: file, cwd
    character(len=len(file)) :: full
    full = file
    if (len_trim(file) == 0 .or. len(cwd) == 0) return
    if (file(1:1) == '/' .or. len(cwd) + 1 + len_trim(file) > len(file)) return
    full = cwd//'/'//trim(file)
  end function absolute

  !> The name after the last '/'.
  pure function base_name(name) result(base)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: base
    base = name(index(name, '/', back=.true.) + 1:)
  end function base_name

  !> The working folder ('' when the system cannot tell: the paths stay as given).
  function working_folder() result(cwd)
    character(len=:), allocatable :: cwd
    character(kind=c_char) :: buf(4096)
    integer :: k
    cwd = ''
    if (.not. c_associated(c_getcwd(buf, size(buf, kind=c_size_t)))) return
    do k = 1, size(buf)
      if (buf(k) == c_null_char) exit
      cwd = cwd//buf(k)
    end do
  end function working_folder

end module voussoir_sweep_row_inputs
