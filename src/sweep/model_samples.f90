!> The model samples of an IDA read from a file (`&sweep model_samples_file`), e.g. the
!> posterior samples of the diagnosis (postproc/voussoir_post/diagnosis/samples.py), so
!> that the fragility is that of the arch as the table tests revealed it.
!>
!> The file is a CSV: `#` comment lines, one header row, one row per sample, columns
!> among the &arch variables of `sample_variables` (friction, contact_inset_m,
!> thickness_m, r_ext_m, size_imperfection; at least one) in any order, and the text
!> columns `sample` and `model`, which are ignored. Any other column is refused with its
!> name: a misspelt column must not be dropped in silence. Each row's values replace
!> those of the base case (sample s gets the size-imperfection pattern of seed
!> `sample_seed + s`, as a Latin hypercube sample does), each checked by the &arch rule
!> of its variable and the sample's whole case by validate_config, with the messages of
!> &arch; every error names the file and the line (and the column).
module voussoir_model_samples
  use, intrinsic :: iso_fortran_env, only: int8, int64
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, join_words
  use voussoir_config, only: config_t, validate_config, resolve_path, arch_rule, arch_rule_text
  use voussoir_input_range, only: need
  use voussoir_numeric_csv, only: read_csv_columns, read_csv_header, csv_cell_len
  use voussoir_sweep_ida, only: sample_variables, sample_case
  implicit none
  private

  public :: read_model_samples, max_model_samples, samples_digest

  integer, parameter :: max_model_samples = 10000   !! rows of a file of model samples at most
  !> Text columns a file of samples may carry (the diagnosis writes them); not read.
  character(len=8), parameter :: ignored_columns(2) = [character(len=8) :: 'sample', 'model']

contains

  !> The model samples of the file `given` (as written in &sweep model_samples_file,
  !> relative to the folder of the input `path`) on the base case `base`: `names` the
  !> columns given (in the order of `sample_variables`), `values(n_params, n_samples)`
  !> the rows, `set_cfg(0:n_samples-1)` the validated case of each sample.
  subroutine read_model_samples(path, given, base, seed, names, values, set_cfg, status)
    character(len=*), intent(in) :: path, given
    type(config_t), intent(in) :: base
    integer, intent(in) :: seed
    character(len=24), allocatable, intent(out) :: names(:)
    real(dp), allocatable, intent(out) :: values(:, :)
    type(config_t), allocatable, intent(out) :: set_cfg(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: file
    character(len=csv_cell_len), allocatable :: header(:)
    integer, allocatable :: lines(:)
    integer :: header_line

    file = trim(resolve_path(path, given))
    call read_csv_header(file, header, header_line, status)
    if (status%ok) call sample_columns(file, header, header_line, base, names, status)
    if (status%ok) call read_csv_columns(file, names, values, lines, status)
    if (status%ok) then
      if (size(values, 2) == 0) then
        call fail(status, file//':'//itoa(header_line)//': no sample rows after the header (one row per model '// &
                  'sample)')
      else if (size(values, 2) > max_model_samples) then
        call fail(status, file//': '//itoa(size(values, 2))//' sample rows; at most '//itoa(max_model_samples))
      end if
    end if
    if (status%ok) call sample_cases(path, file, base, seed, names, values, lines, set_cfg, status)
    if (.not. status%ok) status%message = path//': &sweep model_samples_file: '//trim(status%message)
  end subroutine read_model_samples

  !> The sample columns of the header row `header` (line `header_line` of `file`), in the
  !> order of `sample_variables`; an unknown or repeated column is refused, and so are
  !> the arch's shape (thickness_m, r_ext_m) when the base case is a polygon file.
  subroutine sample_columns(file, header, header_line, base, names, status)
    character(len=*), intent(in) :: file
    character(len=*), intent(in) :: header(:)
    integer, intent(in) :: header_line
    type(config_t), intent(in) :: base
    character(len=24), allocatable, intent(out) :: names(:)
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: at
    logical :: present(size(sample_variables))
    integer :: k, v

    at = file//':'//itoa(header_line)//': '
    present = .false.
    do k = 1, size(header)
      if (any(ignored_columns == header(k))) cycle
      v = findloc(sample_variables, header(k), dim=1)
      if (v == 0) then
        call fail(status, at//"column "//itoa(k)//" '"//trim(header(k))//"' is not a model sample column; the "// &
                  'columns are '//join_words(sample_variables, ', ')//' (at least one), and '// &
                  join_words(ignored_columns, ' and ')//', which are ignored')
        return
      end if
      if (present(v)) then
        call fail(status, at//"column "//itoa(k)//" '"//trim(header(k))//"' appears twice in the header")
        return
      end if
      present(v) = .true.
    end do
    if (.not. any(present)) then
      call fail(status, at//'the header has none of the model sample columns '// &
                join_words(sample_variables, ', '))
      return
    end if
    if (len_trim(base%arch%polygon_file) > 0 .and. (present(3) .or. present(4))) then
      call fail(status, at//'the columns thickness_m and r_ext_m apply to arches, but &arch polygon_file is set')
      return
    end if
    names = pack(sample_variables, present)
  end subroutine sample_columns

  !> The validated case of each row: its values by the &arch rule of their column, then
  !> the whole case (what depends on other variables, e.g. the inset below half the
  !> thickness), each error at the row's line `lines(s)` of `file`.
  subroutine sample_cases(path, file, base, seed, names, values, lines, set_cfg, status)
    character(len=*), intent(in) :: path, file
    type(config_t), intent(in) :: base
    integer, intent(in) :: seed
    character(len=*), intent(in) :: names(:)
    real(dp), intent(in) :: values(:, :)
    integer, intent(in) :: lines(:)
    type(config_t), allocatable, intent(out) :: set_cfg(:)
    type(status_t), intent(inout) :: status
    type(status_t) :: check
    character(len=:), allocatable :: at, inner
    integer :: s, p

    allocate (set_cfg(0:size(values, 2) - 1))
    do s = 1, size(values, 2)
      at = file//':'//itoa(lines(s))
      do p = 1, size(names)
        call need(arch_rule(names(p), values(p, s)), at, 'arch', trim(names(p)), values(p, s), &
                  arch_rule_text(names(p)), status)
      end do
      if (.not. status%ok) return
      set_cfg(s - 1) = sample_case(base, names, values(:, s), seed + s - 1)
      call validate_config(set_cfg(s - 1), check)
      if (.not. check%ok) then
        inner = trim(check%message)
        if (index(inner, path//': ') == 1) inner = inner(len(path) + 3:)
        call fail(status, at//': '//inner)
        return
      end if
    end do
  end subroutine sample_cases

  !> A digest of the samples' values (their bits, row by row), for the sweep definition:
  !> two 32-bit FNV-1a hashes of the bytes, forwards and backwards, as 16 hex digits.
  !> Any change of a value, or of the order of the rows, changes it.
  function samples_digest(values) result(text)
    real(dp), intent(in) :: values(:, :)
    character(len=16) :: text
    integer(int64), parameter :: offset = 2166136261_int64, prime = 16777619_int64, low32 = 4294967295_int64
    integer(int8) :: bytes(storage_size(values)/8*size(values))
    integer(int64) :: forwards, backwards
    integer :: k, n
    bytes = transfer(values, bytes)
    n = size(bytes)
    forwards = offset
    backwards = offset
    do k = 1, n   ! each product is below 2**57: no overflow
      forwards = iand(ieor(forwards, iand(int(bytes(k), int64), 255_int64))*prime, low32)
      backwards = iand(ieor(backwards, iand(int(bytes(n + 1 - k), int64), 255_int64))*prime, low32)
    end do
    write (text, '(2z8.8)') forwards, backwards
  end function samples_digest

end module voussoir_model_samples
