!> The result file of a sweep (layout: docs/results_format.md, "voussoir-sweep").
!>
!> The file is always whole: every update writes the complete state to FILE.part and
!> renames it over FILE (atomic on one file system), so a sweep killed at any instant
!> leaves the last complete FILE behind and, at worst, a stale FILE.part that the next
!> update overwrites. The rows live in memory on the writing rank as `sweep_table_t`
!> (named columns; integers are stored exactly as reals), which is what a resumed sweep
!> reads back.
module voussoir_sweep_output
  use voussoir_kinds, only: dp
  use voussoir_text, only: itoa, fmt_exact
  use voussoir_ordering, only: stable_order
  use voussoir_status, only: status_t, fail
  use voussoir_config, only: config_t, config_entries, config_to_nml
  use voussoir_h5, only: hid_t, h5_create, h5_commit, h5_open_ro, h5_close, h5_group, h5_group_close, h5_write, &
                         h5_attr, commit_text_file, h5_exists, h5_read_real_1d, h5_read_int_1d, &
                         h5_read_attr_string
  use voussoir_run_output, only: write_provenance
  implicit none
  private

  public :: sweep_table_t, sweep_header_t
  public :: results_table, runs_table, dt_check_table, table_init, table_append, table_sort, table_row, table_set, table_value
  public :: write_sweep_file, read_sweep_file, write_sweep_csv, csv_path_of

  integer, parameter :: name_len = 32

  !> Rows of named columns, appended one at a time.
  type :: sweep_table_t
    integer :: n_rows = 0
    character(len=name_len), allocatable :: names(:)
    logical, allocatable :: is_int(:)
    real(dp), allocatable :: values(:, :)   !! (n_columns, capacity)
  end type sweep_table_t

  !> What the file says about the sweep besides its rows.
  type :: sweep_header_t
    type(config_t) :: cfg                           !! the base case (/config, config_nml)
    character(len=16) :: mode = 'threshold'         !! threshold, grid or ida
    character(len=:), allocatable :: signature      !! identifies the sweep definition
    character(len=:), allocatable :: sweep_nml      !! the effective &sweep group
    integer :: n_jobs = 0
    character(len=:), allocatable :: parameter_names  !! comma-separated, possibly empty
    real(dp), allocatable :: parameter_values(:, :)   !! (n_params, n_sets)
    real(dp), allocatable :: frequencies_hz(:)
    real(dp), allocatable :: amplitudes_m(:)          !! grid mode
    character(len=512), allocatable :: record_files(:)  !! ida mode: as given in &sweep record_files
    real(dp), allocatable :: record_pga_m_s2(:), record_pgv_m_s(:)  !! ida mode: of each record, unscaled
  end type sweep_header_t

contains

  !> An empty /results table with the columns of `mode` ('threshold', 'grid' or 'ida').
  function results_table(mode) result(t)
    character(len=*), intent(in) :: mode
    type(sweep_table_t) :: t
    if (mode == 'ida') then
      call table_init(t, [character(len=name_len) :: 'job', 'param_set', 'record', 'scale_stood', &
                          'scale_threshold', 'pga_threshold_m_s2', 'pgv_threshold_m_s', 'censored', &
                          'non_monotonic', 'n_runs', 'mean_iterations', 'wall_time_s', 'failed'], &
                      [.true., .true., .true., .false., .false., .false., .false., .true., .true., .true., &
                       .false., .false., .true.])
    else if (mode == 'grid') then
      call table_init(t, [character(len=name_len) :: 'job', 'param_set', 'frequency_hz', 'amplitude_m', &
                          'collapsed', 'collapse_time_s', 'peak_crown_disp_m', 'mean_iterations', &
                          'nonconverged_steps', 'wall_time_s', 'failed'], &
                      [.true., .true., .false., .false., .true., .false., .false., .false., .true., .false., .true.])
    else
      call table_init(t, [character(len=name_len) :: 'job', 'param_set', 'frequency_hz', 'threshold_m', &
                          'peak_accel_m_s2', 'non_monotonic', 'n_runs', 'mean_iterations', &
                          'stand_below_m', 'static_onset_m', 'wall_time_s', 'failed'], &
                      [.true., .true., .false., .false., .false., .true., .true., .false., .false., &
                       .false., .false., .true.])
    end if
  end function results_table

  !> An empty /runs table: every simulation of the searches; `value_name` is the
  !> searched variable ('amplitude_m', or 'scale' in an IDA).
  function runs_table(value_name) result(t)
    character(len=*), intent(in) :: value_name
    type(sweep_table_t) :: t
    call table_init(t, [character(len=name_len) :: 'job', 'run', value_name, 'collapsed', &
                        'collapse_time_s', 'peak_crown_disp_m', 'mean_iterations', 'n_steps', &
                        'nonconverged_steps', 'wall_time_s', 'failed'], &
                    [.true., .true., .false., .true., .false., .false., .false., .true., .true., .false., .true.])
  end function runs_table

  !> An empty /dt_check table: runs of an IDA redone at half the time step.
  function dt_check_table() result(t)
    type(sweep_table_t) :: t
    call table_init(t, [character(len=name_len) :: 'job', 'scale', 'collapsed', 'collapsed_half_dt'], &
                    [.true., .false., .true., .true.])
  end function dt_check_table

  !> An empty table with the columns `names` (integer where `is_int`).
  subroutine table_init(t, names, is_int)
    type(sweep_table_t), intent(out) :: t
    character(len=*), intent(in) :: names(:)
    logical, intent(in) :: is_int(:)
    t%names = names
    t%is_int = is_int
    allocate (t%values(size(names), 64))
    t%n_rows = 0
  end subroutine table_init

  !> Append one row; `row` holds the columns in the table's order.
  subroutine table_append(t, row)
    type(sweep_table_t), intent(inout) :: t
    real(dp), intent(in) :: row(:)
    real(dp), allocatable :: grown(:, :)
    if (t%n_rows == size(t%values, 2)) then
      allocate (grown(size(t%values, 1), 2*size(t%values, 2)))
      grown(:, 1:t%n_rows) = t%values(:, 1:t%n_rows)
      call move_alloc(grown, t%values)
    end if
    t%n_rows = t%n_rows + 1
    t%values(:, t%n_rows) = row
  end subroutine table_append

  !> A row of zeros for `t`, to fill with `table_set`.
  pure subroutine table_row(t, row)
    type(sweep_table_t), intent(in) :: t
    real(dp), allocatable, intent(out) :: row(:)
    allocate (row(size(t%names)))
    row = 0.0_dp
  end subroutine table_row

  !> The value of column `name` in row `r` (0 if there is no such column).
  pure real(dp) function table_value(t, name, r)
    type(sweep_table_t), intent(in) :: t
    character(len=*), intent(in) :: name
    integer, intent(in) :: r
    integer :: k
    k = column_index(t, name)
    table_value = 0.0_dp
    if (k > 0) table_value = t%values(k, r)
  end function table_value

  !> Set column `name` of `row` (a row of `t`) to `x` (a name `t` lacks is ignored).
  pure subroutine table_set(t, row, name, x)
    type(sweep_table_t), intent(in) :: t
    real(dp), intent(inout) :: row(:)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x
    integer :: k
    k = column_index(t, name)
    if (k > 0) row(k) = x
  end subroutine table_set


  pure integer function column_index(t, name)
    type(sweep_table_t), intent(in) :: t
    character(len=*), intent(in) :: name
    integer :: k
    column_index = 0
    do k = 1, size(t%names)
      if (t%names(k) == name) then
        column_index = k
        return
      end if
    end do
  end function column_index

  !> Sort the rows by the columns `keys` (first key first), stably.
  subroutine table_sort(t, keys)
    type(sweep_table_t), intent(inout) :: t
    character(len=*), intent(in) :: keys(:)
    integer, allocatable :: key_col(:)
    integer :: k, n
    n = t%n_rows
    if (n < 2) return
    allocate (key_col(size(keys)))
    do k = 1, size(keys)
      key_col(k) = column_index(t, keys(k))
    end do
    key_col = pack(key_col, key_col > 0)
    t%values(:, 1:n) = t%values(:, stable_order(t%values(key_col, 1:n)))
  end subroutine table_sort

  !> Write the whole sweep file `path` through `path`.part. `runs` may have no columns
  !> (grid mode): then there is no /runs group. `complete` marks a finished sweep.
  !> `dt_check`, when given, is the time-step check of an IDA (/dt_check).
  subroutine write_sweep_file(path, header, results, runs, complete, status, dt_check)
    character(len=*), intent(in) :: path
    type(sweep_header_t), intent(in) :: header
    type(sweep_table_t), intent(in) :: results, runs
    logical, intent(in) :: complete
    type(status_t), intent(inout) :: status
    type(sweep_table_t), intent(in), optional :: dt_check
    integer(hid_t) :: file_id, g

    call h5_create(trim(path), file_id, status)
    if (.not. status%ok) return
    call write_provenance(file_id, 'voussoir-sweep', header%cfg, status)
    call h5_attr(file_id, 'config_nml', config_to_nml(config_entries(header%cfg))//header%sweep_nml, status)
    call h5_attr(file_id, 'mode', trim(header%mode), status)
    call h5_attr(file_id, 'sweep_signature', header%signature, status)
    call h5_attr(file_id, 'n_jobs', header%n_jobs, status)
    call h5_attr(file_id, 'parameter_names', header%parameter_names, status)
    call h5_attr(file_id, 'complete', merge(1, 0, complete), status)

    call h5_group(file_id, 'sweep', g, status)
    if (header%mode == 'ida') then
      call h5_attr(file_id, 'record_files', join_lines(header%record_files), status)
      call h5_write(g, 'record_pga_m_s2', header%record_pga_m_s2, status)
      call h5_write(g, 'record_pgv_m_s', header%record_pgv_m_s, status)
    else
      call h5_write(g, 'frequencies_hz', header%frequencies_hz, status)
    end if
    if (header%mode == 'grid') call h5_write(g, 'amplitudes_m', header%amplitudes_m, status)
    call h5_group_close(g, status)
    if (size(header%parameter_values, 1) > 0) then
      call h5_group(file_id, 'parameters', g, status)
      call h5_write(g, 'values', header%parameter_values, status)
      call h5_group_close(g, status)
    end if
    call write_table(file_id, 'results', results, status)
    if (allocated(runs%names)) then
      if (size(runs%names) > 0) call write_table(file_id, 'runs', runs, status)
    end if
    if (present(dt_check)) then
      call write_table(file_id, 'dt_check', dt_check, status)
      call h5_attr(file_id, 'dt_check_runs', dt_check%n_rows, status)
      call h5_attr(file_id, 'dt_check_changed', count(dt_check%values(3, 1:dt_check%n_rows) /= &
                                                      dt_check%values(4, 1:dt_check%n_rows)), status)
    end if
    call h5_commit(file_id, trim(path), status)
  end subroutine write_sweep_file

  !> The entries of `lines`, trimmed, one per line.
  function join_lines(lines) result(text)
    character(len=*), intent(in) :: lines(:)
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, size(lines)
      text = text//trim(lines(k))
      if (k < size(lines)) text = text//achar(10)
    end do
  end function join_lines

  subroutine write_table(file_id, name, t, status)
    integer(hid_t), intent(in) :: file_id
    character(len=*), intent(in) :: name
    type(sweep_table_t), intent(in) :: t
    type(status_t), intent(inout) :: status
    integer(hid_t) :: g
    integer :: k
    real(dp), allocatable :: column(:)   ! contiguous copy of a row of `values`
    allocate (column(t%n_rows))
    call h5_group(file_id, name, g, status)
    do k = 1, size(t%names)
      column = t%values(k, 1:t%n_rows)
      if (t%is_int(k)) then
        call h5_write(g, trim(t%names(k)), nint(column), status)
      else
        call h5_write(g, trim(t%names(k)), column, status)
      end if
    end do
    call h5_group_close(g, status)
  end subroutine write_table

  !> Read back the rows of an earlier run of the same sweep from `path` into `results`
  !> and `runs` (initialised with their columns), and the code version that wrote them.
  !> The file must come from voussoir-sweep and carry `signature`; otherwise a clear error.
  subroutine read_sweep_file(path, signature, results, runs, written_by, status)
    character(len=*), intent(in) :: path, signature
    type(sweep_table_t), intent(inout) :: results, runs
    character(len=:), allocatable, intent(out) :: written_by
    type(status_t), intent(inout) :: status
    integer(hid_t) :: file_id
    character(len=:), allocatable :: producer, stored

    call h5_open_ro(trim(path), file_id, status)
    if (.not. status%ok) then
      call fail(status, trim(path)//': exists but is not a readable HDF5 file; '// &
                'move it away or set &output file to another name')
      return
    end if
    producer = h5_read_attr_string(file_id, 'producer')
    written_by = h5_read_attr_string(file_id, 'code_version')
    stored = h5_read_attr_string(file_id, 'sweep_signature')
    if (producer /= 'voussoir-sweep') then
      if (len(producer) == 0) producer = 'none: not HDF5, or not a voussoir result'
      call fail(status, trim(path)//': exists and was not written by voussoir-sweep (producer: '// &
                producer//'); it is left alone: move it away or set &output file to another name')
    else if (stored /= signature) then
      call fail(status, trim(path)//': holds a different sweep ('//first_difference(stored, signature)// &
                '); it is left alone, never mixed: move it away or set &output file to another name')
    end if
    if (status%ok) call read_table(file_id, 'results', results, status)
    if (status%ok .and. allocated(runs%names)) then
      if (size(runs%names) > 0) call read_table(file_id, 'runs', runs, status)
    end if
    call h5_close(file_id, status)

  contains

    subroutine read_table(loc, name, t, st)
      integer(hid_t), intent(in) :: loc
      character(len=*), intent(in) :: name
      type(sweep_table_t), intent(inout) :: t
      type(status_t), intent(inout) :: st
      integer(hid_t) :: g
      real(dp), allocatable :: x(:)
      integer, allocatable :: ix(:)
      real(dp), allocatable :: cols(:, :)
      integer :: k, n
      if (.not. h5_exists(loc, name)) then
        call fail(st, trim(path)//': has no /'//name//' group')
        return
      end if
      call h5_group(loc, name, g, st)
      n = -1
      do k = 1, size(t%names)
        if (.not. h5_exists(g, trim(t%names(k)))) then
          call fail(st, trim(path)//': /'//name//'/'//trim(t%names(k))//' is missing')
          exit
        end if
        if (t%is_int(k)) then
          call h5_read_int_1d(g, trim(t%names(k)), ix, st)
          x = real(ix, dp)
        else
          call h5_read_real_1d(g, trim(t%names(k)), x, st)
        end if
        if (.not. st%ok) exit
        if (n < 0) then
          n = size(x)
          allocate (cols(size(t%names), n))
        else if (size(x) /= n) then
          call fail(st, trim(path)//': the columns of /'//name//' differ in length')
          exit
        end if
        cols(k, :) = x
      end do
      call h5_group_close(g, st)
      if (.not. st%ok) return
      do k = 1, n
        call table_append(t, cols(:, k))
      end do
    end subroutine read_table

  end subroutine read_sweep_file

  !> Where two signatures first differ, for the message: the line of each.
  function first_difference(stored, wanted) result(text)
    character(len=*), intent(in) :: stored, wanted
    character(len=:), allocatable :: text, line_s, line_w
    integer :: line, ps, pw
    character(len=12) :: num
    ps = 1
    pw = 1
    line = 0
    do
      line = line + 1
      call next_line(stored, ps, line_s)
      call next_line(wanted, pw, line_w)
      if (line_s /= line_w) exit
      if (ps > len(stored) .and. pw > len(wanted)) exit
    end do
    write (num, '(i0)') line
    text = 'signature line '//trim(num)//": the file has '"//trim(adjustl(line_s))// &
           "', this input gives '"//trim(adjustl(line_w))//"'"
  contains
    subroutine next_line(s, p, l)
      character(len=*), intent(in) :: s
      integer, intent(inout) :: p
      character(len=:), allocatable, intent(out) :: l
      integer :: e
      if (p > len(s)) then
        l = '(end)'
        return
      end if
      e = index(s(p:), achar(10))
      if (e == 0) then
        l = s(p:)
        p = len(s) + 1
      else
        l = s(p:p + e - 2)
        p = p + e
      end if
    end subroutine next_line
  end function first_difference

  !> The CSV summary beside `h5_path`: same name, extension .csv.
  function csv_path_of(h5_path) result(csv)
    character(len=*), intent(in) :: h5_path
    character(len=:), allocatable :: csv
    integer :: dot, slash
    dot = index(h5_path, '.', back=.true.)
    slash = index(h5_path, '/', back=.true.)
    if (dot > slash + 1) then
      csv = trim(h5_path(:dot - 1))//'.csv'
    else
      csv = trim(h5_path)//'.csv'
    end if
  end function csv_path_of

  !> The plain CSV summary (rows in the order of `results`), written through a
  !> temporary file and renamed.
  subroutine write_sweep_csv(path, header, results, status)
    character(len=*), intent(in) :: path
    type(sweep_header_t), intent(in) :: header
    type(sweep_table_t), intent(in) :: results
    type(status_t), intent(inout) :: status
    integer :: r, k, set, n_params
    character(len=:), allocatable :: text, line, names
    character(len=*), parameter :: nl = achar(10)

    n_params = size(header%parameter_values, 1)
    names = ''
    if (n_params > 0) names = ','//header%parameter_names
    if (header%mode == 'ida') then
      text = 'record,param_set'//names//',scale_stood,scale_threshold,pga_threshold_m_s2,pgv_threshold_m_s,'// &
             'censored,non_monotonic,n_runs,failed'//nl
    else if (header%mode == 'grid') then
      text = 'param_set'//names//',frequency_hz,amplitude_m,outcome,collapse_time_s,peak_crown_disp_m,'// &
             'mean_iterations'//nl
    else
      text = 'param_set'//names//',frequency_hz,threshold_m,peak_accel_m_s2,non_monotonic,failed'//nl
    end if
    do r = 1, results%n_rows
      set = nint(col('param_set'))
      line = itoa(set)
      if (header%mode == 'ida') line = trim(header%record_files(nint(col('record')) + 1))//','//line
      do k = 1, n_params
        line = line//','//fmt_exact(header%parameter_values(k, set + 1))
      end do
      if (header%mode == 'ida') then
        line = line//','//fmt_exact(col('scale_stood'))//','//fmt_exact(col('scale_threshold'))//','// &
               fmt_exact(col('pga_threshold_m_s2'))//','//fmt_exact(col('pgv_threshold_m_s'))//','// &
               itoa(nint(col('censored')))//','//itoa(nint(col('non_monotonic')))//','//itoa(nint(col('n_runs')))// &
               ','//itoa(nint(col('failed')))
        text = text//line//nl
        cycle
      end if
      line = line//','//fmt_exact(col('frequency_hz'))
      if (header%mode == 'grid') then
        line = line//','//fmt_exact(col('amplitude_m'))//','// &
               trim(outcome_word())//','// &
               fmt_exact(col('collapse_time_s'))//','//fmt_exact(col('peak_crown_disp_m'))//','// &
               fmt_exact(col('mean_iterations'))
      else
        line = line//','//fmt_exact(col('threshold_m'))//','//fmt_exact(col('peak_accel_m_s2'))//','// &
               itoa(nint(col('non_monotonic')))//','//itoa(nint(col('failed')))
      end if
      text = text//line//nl
    end do
    call commit_text_file(path, text, status)

  contains

    real(dp) function col(name)
      character(len=*), intent(in) :: name
      col = results%values(column_index(results, name), r)
    end function col

    !> A grid run's outcome: collapse, stand, or failed (the run stopped with an error).
    function outcome_word() result(word)
      character(len=:), allocatable :: word
      if (nint(col('failed')) == 1) then
        word = 'failed'
      else if (nint(col('collapsed')) == 1) then
        word = 'collapse'
      else
        word = 'stand'
      end if
    end function outcome_word

  end subroutine write_sweep_csv


end module voussoir_sweep_output
