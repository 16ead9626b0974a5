!> The tables of a sweep in memory: rows of named columns (integers stored exactly as
!> reals), appended one at a time, sorted, and read back by name. The result file writes
!> them (src/io/sweep_output.f90); the modes say which columns they have.
module voussoir_sweep_table
  use voussoir_kinds, only: dp
  use voussoir_ordering, only: stable_order
  implicit none
  private

  public :: sweep_table_t, named_values_t, named_text_t, name_len
  public :: runs_table, table_init, table_append, table_sort, table_row, table_set, table_value, &
            column_index

  integer, parameter :: name_len = 32

  !> Rows of named columns, appended one at a time.
  type :: sweep_table_t
    integer :: n_rows = 0
    character(len=name_len), allocatable :: names(:)
    logical, allocatable :: is_int(:)
    real(dp), allocatable :: values(:, :)   !! (n_columns, capacity)
  end type sweep_table_t

  !> A named list of reals that a sweep file keeps besides its tables (/sweep/<name>).
  type :: named_values_t
    character(len=name_len) :: name = ''
    real(dp), allocatable :: values(:)
  end type named_values_t

  !> A named text that a sweep file keeps as an attribute.
  type :: named_text_t
    character(len=name_len) :: name = ''
    character(len=:), allocatable :: text
  end type named_text_t

contains

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

  !> The column of `t` named `name` (0 if none).
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

end module voussoir_sweep_table
