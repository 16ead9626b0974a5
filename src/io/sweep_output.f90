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
  use voussoir_text, only: itoa, fmt_exact, join_words
  use voussoir_status, only: status_t, fail
  use voussoir_config, only: config_t, config_entries, config_to_nml
  use voussoir_h5, only: hid_t, h5_create, h5_commit, h5_open_ro, h5_close, h5_group, h5_group_close, h5_write, &
                         h5_attr, commit_text_file, h5_exists, h5_read_real_1d, h5_read_int_1d, &
                         h5_read_attr_string
  use voussoir_run_output, only: write_provenance
  use voussoir_sweep_table, only: sweep_table_t, named_values_t, named_text_t, table_append, table_value
  use voussoir_sweep_mode, only: sweep_plan_t
  implicit none
  private

  public :: sweep_header_t
  public :: write_sweep_file, read_sweep_file, write_sweep_csv, csv_path_of

  !> What the file says about the sweep besides its rows.
  type :: sweep_header_t
    type(config_t) :: cfg                           !! the base case (/config, config_nml)
    character(len=16) :: mode = ''                  !! the name of the sweep's mode
    character(len=:), allocatable :: signature      !! identifies the sweep definition
    character(len=:), allocatable :: sweep_nml      !! the effective &sweep group
    integer :: n_jobs = 0
    character(len=:), allocatable :: parameter_names  !! comma-separated, possibly empty
    real(dp), allocatable :: parameter_values(:, :)   !! (n_params, n_sets)
    type(named_values_t), allocatable :: datasets(:)  !! the mode's lists under /sweep
    type(named_text_t), allocatable :: attributes(:)  !! the mode's attributes of the file
  end type sweep_header_t

contains

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
    integer :: k

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
    do k = 1, size(header%attributes)
      call h5_attr(file_id, trim(header%attributes(k)%name), header%attributes(k)%text, status)
    end do
    do k = 1, size(header%datasets)
      call h5_write(g, trim(header%datasets(k)%name), header%datasets(k)%values, status)
    end do
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
          call fail(st, trim(path)//': /'//name//'/'//trim(t%names(k))//' is missing (a file of an earlier '// &
                    'version, without that column? It cannot be continued: move it away and run the sweep anew)')
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

  !> The plain CSV summary (rows in the order of `results`, columns of the plan's
  !> mode), written through a temporary file and renamed.
  subroutine write_sweep_csv(path, plan, results, status)
    character(len=*), intent(in) :: path
    type(sweep_plan_t), intent(in) :: plan
    type(sweep_table_t), intent(in) :: results
    type(status_t), intent(inout) :: status
    integer :: r, k, set
    character(len=:), allocatable :: text, set_columns, names
    character(len=*), parameter :: nl = achar(10)

    names = ''
    if (plan%n_params > 0) names = ','//join_words(plan%param_names, ',')
    text = plan%mode%csv_header(names)//nl
    do r = 1, results%n_rows
      set = nint(table_value(results, 'param_set', r))
      set_columns = itoa(set)
      do k = 1, plan%n_params
        set_columns = set_columns//','//fmt_exact(plan%param_values(k, set + 1))
      end do
      text = text//plan%mode%csv_line(plan, results, r, set_columns)//nl
    end do
    call commit_text_file(path, text, status)
  end subroutine write_sweep_csv

end module voussoir_sweep_output
