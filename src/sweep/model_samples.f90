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
!>
!> Comment lines before the header, when present, say what the samples are for
!> (samples.py writes them): `# format: voussoir posterior samples 1`, the layout's
!> version; `# model version: 1`, the version of the meaning of the sampled values
!> (voussoir_version's model_version: the contact inset, the thickness factor, the
!> friction law...); `# code: voussoir-post 0.1.0`, the code that wrote the file (read
!> for the provenance of the sweep's file); and `# nominal arch: embrace_deg = 156.0,
!> n_voussoirs = 13, ...`, the specimen's &arch values the samples are relative to. A
!> format this reader does not know is refused, and so is a model version other than
!> this code's or a format line without a model version (a file of another code
!> version), and a nominal arch unlike the IDA's base &arch (another specimen or
!> campaign: reals within 1e-9 relative). A file without a format line (made by hand) is
!> read unchecked, and a note says so.
module voussoir_model_samples
  use, intrinsic :: iso_fortran_env, only: int8, int64
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: itoa, join_words, fmt_real
  use voussoir_config, only: config_t, validate_config, resolve_path, arch_rule, arch_rule_text
  use voussoir_input_range, only: need
  use voussoir_numeric_csv, only: read_csv_columns, read_csv_header, csv_cell_len
  use voussoir_version, only: model_version
  use voussoir_sweep_ida, only: sample_variables, sample_case
  implicit none
  private

  public :: read_model_samples, max_model_samples, samples_digest

  integer, parameter :: max_model_samples = 10000   !! rows of a file of model samples at most
  !> Text columns a file of samples may carry (the diagnosis writes them); not read.
  character(len=8), parameter :: ignored_columns(2) = [character(len=8) :: 'sample', 'model']
  !> The layout this reader knows, as the `# format:` line names it.
  character(len=*), parameter :: known_format = 'voussoir posterior samples 1'
  character(len=*), parameter :: format_prefix = '# format:', nominal_prefix = '# nominal arch:', &
                                 model_prefix = '# model version:', code_prefix = '# code:'
  !> The &arch variables of the nominal arch line, all of them needed.
  character(len=13), parameter :: nominal_keys(6) = [character(len=13) :: 'embrace_deg', 'n_voussoirs', &
                                                     'r_ext_m', 'thickness_m', 'width_m', 'density_kg_m3']
  real(dp), parameter :: nominal_rel_tol = 1.0e-9_dp   !! a nominal value and the base's agree within this

contains

  !> The model samples of the file `given` (as written in &sweep model_samples_file,
  !> relative to the folder of the input `path`) on the base case `base`: `names` the
  !> columns given (in the order of `sample_variables`), `values(n_params, n_samples)`
  !> the rows, `set_cfg(0:n_samples-1)` the validated case of each sample; `note` a line
  !> for the log when the file could not be checked against the base case ('' if it was);
  !> `code` the file's `# code:` line without its prefix ('' without one).
  subroutine read_model_samples(path, given, base, seed, names, values, set_cfg, note, code, status)
    character(len=*), intent(in) :: path, given
    type(config_t), intent(in) :: base
    integer, intent(in) :: seed
    character(len=24), allocatable, intent(out) :: names(:)
    real(dp), allocatable, intent(out) :: values(:, :)
    type(config_t), allocatable, intent(out) :: set_cfg(:)
    character(len=:), allocatable, intent(out) :: note, code
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: file
    character(len=csv_cell_len), allocatable :: header(:)
    integer, allocatable :: lines(:)
    integer :: header_line

    note = ''
    code = ''
    file = trim(resolve_path(path, given))
    call read_csv_header(file, header, header_line, status)
    if (status%ok) call check_provenance(file, base, note, code, status)
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

  !> The `# format:`, `# model version:`, `# code:` and `# nominal arch:` comment lines of
  !> `file` (before its header): refused when the format is not `known_format`, when the
  !> model version is not this code's `model_version`, when a format line comes without
  !> a model version or a nominal arch, or when the nominal arch is not the base case's
  !> &arch; without a format and a nominal arch, `note` says that the file could not be
  !> checked. `code` gets the text of the `# code:` line.
  subroutine check_provenance(file, base, note, code, status)
    character(len=*), intent(in) :: file
    type(config_t), intent(in) :: base
    character(len=:), allocatable, intent(inout) :: note, code
    type(status_t), intent(inout) :: status
    character(len=1024) :: line
    character(len=512) :: iomsg
    character(len=:), allocatable :: text
    integer :: unit, ios, line_no
    logical :: has_format, has_nominal, has_model

    has_format = .false.
    has_nominal = .false.
    has_model = .false.
    open (newunit=unit, file=file, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call fail(status, file//': cannot open: '//trim(iomsg))
      return
    end if
    line_no = 0
    do
      read (unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      line_no = line_no + 1
      text = trim(adjustl(line))
      if (len(text) > 0) then
        if (text(len(text):) == achar(13)) text = trim(text(:len(text) - 1))
      end if
      if (len(text) == 0) cycle
      if (text(1:1) /= '#') exit   ! the header row: the comments before it are read
      if (index(text, format_prefix) == 1) then
        has_format = .true.
        text = trim(adjustl(text(len(format_prefix) + 1:)))
        if (text /= known_format) then
          call fail(status, file//':'//itoa(line_no)//": format '"//text//"' is not one this code reads ('"// &
                    known_format//"'): a file of another code version")
          exit
        end if
      else if (index(text, model_prefix) == 1) then
        has_model = .true.
        call check_model_version(file//':'//itoa(line_no)//': ', trim(adjustl(text(len(model_prefix) + 1:))), status)
        if (.not. status%ok) exit
      else if (index(text, code_prefix) == 1) then
        code = trim(adjustl(text(len(code_prefix) + 1:)))
      else if (index(text, nominal_prefix) == 1) then
        has_nominal = .true.
        call check_nominal(file//':'//itoa(line_no)//': ', text(len(nominal_prefix) + 1:), base, status)
        if (.not. status%ok) exit
      end if
    end do
    close (unit)
    if (.not. status%ok) return
    if (has_format .and. .not. has_model) then
      call fail(status, file//": format '"//known_format//"' but no '"//model_prefix//"' line: written by a "// &
                'code from before model versions (this code''s model is version '//itoa(model_version)// &
                '): rerun voussoir-diagnose on the campaign')
    else if (has_format .and. .not. has_nominal) then
      call fail(status, file//": format '"//known_format//"' but no '"//nominal_prefix//"' line: the file is "// &
                'incomplete')
    else if (.not. has_nominal) then
      note = 'note: '//file//" has no '"//nominal_prefix//"' line (a hand-made file?): its samples could not "// &
             'be checked against the base &arch'
    end if
  end subroutine check_provenance

  !> The model version `text` of a `# model version:` line against this code's
  !> `model_version`: another number means the samples' values mean something else here.
  subroutine check_model_version(at, text, status)
    character(len=*), intent(in) :: at, text
    type(status_t), intent(inout) :: status
    integer :: version, ios
    read (text, *, iostat=ios) version
    if (ios /= 0 .or. verify(text, '0123456789') /= 0 .or. len(text) == 0) then
      call fail(status, at//"model version '"//text//"' is not a whole number")
    else if (version /= model_version) then
      call fail(status, at//'written by a code whose model is version '//itoa(version)//'; this code''s is '// &
                itoa(model_version)//': rerun voussoir-diagnose on the campaign')
    end if
  end subroutine check_model_version

  !> The nominal arch `text` ("embrace_deg = 156.0, n_voussoirs = 13, ...") against the
  !> base case's &arch: every one of `nominal_keys` once, each within `nominal_rel_tol`.
  subroutine check_nominal(at, text, base, status)
    character(len=*), intent(in) :: at, text
    type(config_t), intent(in) :: base
    type(status_t), intent(inout) :: status
    real(dp) :: nominal(size(nominal_keys)), base_value(size(nominal_keys)), value
    logical :: seen(size(nominal_keys))
    character(len=:), allocatable :: item, key
    integer :: start, comma, eq, k, ios

    associate (a => base%arch)
      base_value = [a%embrace_deg, real(a%n_voussoirs, dp), a%r_ext_m, a%thickness_m, a%width_m, a%density_kg_m3]
    end associate
    seen = .false.
    start = 1
    do while (start <= len(text))
      comma = index(text(start:), ',')
      if (comma == 0) comma = len(text) - start + 2
      item = trim(adjustl(text(start:start + comma - 2)))
      start = start + comma
      eq = index(item, '=')
      key = trim(item(:max(eq - 1, 0)))
      k = findloc(nominal_keys, key, dim=1)
      if (eq == 0 .or. k == 0) then
        call fail(status, at//"nominal arch: '"//item//"' is not 'name = value' with a name among "// &
                  join_words(nominal_keys, ', '))
        return
      end if
      read (item(eq + 1:), *, iostat=ios) value
      if (ios /= 0) then
        call fail(status, at//'nominal arch: '//key//" = '"//trim(adjustl(item(eq + 1:)))//"' is not a number")
        return
      end if
      seen(k) = .true.
      nominal(k) = value
    end do
    if (.not. all(seen)) then
      call fail(status, at//'nominal arch: '//trim(nominal_keys(findloc(seen, .false., dim=1)))//' is missing '// &
                '(the line gives '//join_words(nominal_keys, ', ')//')')
      return
    end if
    do k = 1, size(nominal_keys)
      if (abs(nominal(k) - base_value(k)) > nominal_rel_tol*max(abs(nominal(k)), abs(base_value(k)))) then
        call fail(status, at//'the samples are relative to the nominal arch '//trim(nominal_keys(k))//' = '// &
                  fmt_real(nominal(k))//', but the base &arch has '//trim(nominal_keys(k))//' = '// &
                  fmt_real(base_value(k))//': samples of another specimen or campaign')
        return
      end if
    end do
  end subroutine check_nominal

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
