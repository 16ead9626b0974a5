!> One namelist group as a table: each variable declared once (its name, a pointer to
!> the component it fills, its unit, its allowed range or choices) and everything else
!> follows from the table: the read (unknown names, types, list lengths, each refusal
!> naming the file, line, variable, what it expects and what it got), the range checks
!> (one message, voussoir_input_range), the effective settings of the result files, and
!> the list of variables in messages.
!>
!> Use: declare the table on the object the group fills (a `target`), then read:
!>
!>     call g%add('dt_s', cfg%solver%dt_s, unit='s', range='0 < dt_s <= 0.1')
!>     call g%add('waveform', cfg%motion%waveform, choices=waveform_names)
!>     call g%add('joint_friction', cfg%arch%joint_friction, first=0, unset=unset_friction)
!>     call g%read(path, status)         ! absent group: the values stay as they were
!>     call g%check(path, status)        ! every range and choice without `when`
!>     n = g%length('frequencies_hz', path, status)  ! a sparse list's entries, without gaps
!>
!> A range with `when` is checked on request only (`g%check(path, status, when=...)`):
!> the case it belongs to (a waveform, the arch builder); `when=checked_apart` marks a
!> variable's own range that the caller checks against other variables instead.
module voussoir_namelist_group
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, itoa, join_words, fmt_real
  use voussoir_namelist_text, only: nml_value_t, nml_assignment_t, read_group_text
  use voussoir_input_range, only: range_t, range_of, in_range, need
  implicit none
  private

  public :: nml_group_t, config_entry_t, checked_apart, value_len

  integer, parameter :: value_len = 512   !! characters of an effective setting's value
  !> `when` of a range the caller checks itself, against other variables.
  character(len=*), parameter :: checked_apart = '(checked apart)'

  !> One effective setting: group, name, type ('r', 'i', 'l', 's') and value as text.
  type :: config_entry_t
    character(len=16) :: group = ''
    character(len=32) :: name = ''
    character(len=1) :: kind = 's'
    character(len=value_len) :: value = ''
  end type config_entry_t

  !> A text the table fills (a deferred-length pointer per entry: gfortran 12 cannot
  !> write through a deferred-length character array pointer).
  type :: text_ref_t
    character(len=:), pointer :: s => null()
  end type text_ref_t

  !> One variable of a group.
  type :: nml_var_t
    character(len=32) :: name = ''
    character(len=1) :: kind = 'r'            !! 'r', 'i', 'l' or 's', as config_entry_t
    character(len=:), allocatable :: about    !! type and unit, for messages
    type(range_t) :: range                    !! allowed range (text '' for none)
    character(len=32), allocatable :: choices(:)  !! allowed texts (lower case), if any
    character(len=:), allocatable :: when     !! '' or the case its range and choices apply to
    logical :: list = .false.
    integer :: first = 1                      !! index of a list's first entry
    logical :: sparse = .false.               !! a list's entries, or a real, at `unset` are not settings
    real(dp) :: unset_real = 0.0_dp
    integer :: unset_integer = 0
    real(dp), pointer :: r => null(), ra(:) => null()
    integer, pointer :: i => null(), ia(:) => null()
    logical, pointer :: l => null(), la(:) => null()
    character(len=:), pointer :: t => null()
    type(text_ref_t), allocatable :: ta(:)
  end type nml_var_t

  !> A namelist group: its name and its variables, in the order of the effective settings.
  type :: nml_group_t
    character(len=16) :: name = ''
    type(nml_var_t), allocatable :: vars(:)
  contains
    procedure, private :: add_real, add_integer, add_logical, add_text
    procedure, private :: add_real_list, add_integer_list, add_logical_list, add_text_list
    generic :: add => add_real, add_integer, add_logical, add_text, add_real_list, add_integer_list, &
                      add_logical_list, add_text_list
    procedure :: read => read_group
    procedure :: check => check_group
    procedure :: entries => group_entries
    procedure :: variables => group_variables
    procedure :: find => find_var
    procedure :: length => list_length
  end type nml_group_t

  interface
    !> Read group `g%name` of `path` into the table's targets (namelist_group_read.f90).
    module subroutine read_group(g, path, status, found)
      class(nml_group_t), intent(in) :: g
      character(len=*), intent(in) :: path
      type(status_t), intent(inout) :: status
      logical, intent(out), optional :: found
    end subroutine read_group
  end interface

contains

  !> A variable with the attributes every kind shares.
  function new_var(name, kind, unit, range, when, about) result(v)
    character(len=*), intent(in) :: name, kind
    character(len=*), intent(in), optional :: unit, range, when, about
    type(nml_var_t) :: v
    v%name = name
    v%kind = kind
    select case (kind)
    case ('r')
      v%about = 'real'
    case ('i')
      v%about = 'integer'
    case ('l')
      v%about = 'logical'
    case default
      v%about = 'text'
    end select
    if (present(unit)) v%about = v%about//', '//unit
    if (present(about)) v%about = about
    v%range = range_t(text='')
    if (present(range)) v%range = range_of(range, name)
    v%when = ''
    if (present(when)) v%when = when
    allocate (v%choices(0))
  end function new_var

  subroutine append(g, v)
    class(nml_group_t), intent(inout) :: g
    type(nml_var_t), intent(in) :: v
    if (.not. allocated(g%vars)) allocate (g%vars(0))
    g%vars = [g%vars, v]
  end subroutine append

  !> A real; with `unset`, a value that another one stands in for: at `unset` it is no
  !> setting (neither range-checked nor among the effective settings).
  subroutine add_real(g, name, x, unit, range, when, about, unset)
    class(nml_group_t), intent(inout) :: g
    character(len=*), intent(in) :: name
    real(dp), intent(inout), target :: x
    character(len=*), intent(in), optional :: unit, range, when, about
    real(dp), intent(in), optional :: unset
    type(nml_var_t) :: v
    v = new_var(name, 'r', unit, range, when, about)
    v%r => x
    v%sparse = present(unset)
    if (present(unset)) v%unset_real = unset
    call append(g, v)
  end subroutine add_real

  subroutine add_integer(g, name, x, unit, range, when, about)
    class(nml_group_t), intent(inout) :: g
    character(len=*), intent(in) :: name
    integer, intent(inout), target :: x
    character(len=*), intent(in), optional :: unit, range, when, about
    type(nml_var_t) :: v
    v = new_var(name, 'i', unit, range, when, about)
    v%i => x
    call append(g, v)
  end subroutine add_integer

  subroutine add_logical(g, name, x, about)
    class(nml_group_t), intent(inout) :: g
    character(len=*), intent(in) :: name
    logical, intent(inout), target :: x
    character(len=*), intent(in), optional :: about
    type(nml_var_t) :: v
    v = new_var(name, 'l', about=about)
    v%l => x
    call append(g, v)
  end subroutine add_logical

  !> A text; with `choices`, one of them (read in any case, kept in lower case).
  subroutine add_text(g, name, x, choices, when, about)
    class(nml_group_t), intent(inout) :: g
    character(len=*), intent(in) :: name
    character(len=*), intent(inout), target :: x
    character(len=*), intent(in), optional :: choices(:), when, about
    type(nml_var_t) :: v
    v = new_var(name, 's', when=when, about=about)
    if (present(choices)) then
      v%choices = choices
      if (.not. present(about)) v%about = "'"//join_words(choices, "'|'")//"'"
    end if
    v%t => x
    call append(g, v)
  end subroutine add_text

  !> A list x(first:); with `unset`, only the entries that differ from it are settings.
  subroutine add_real_list(g, name, x, first, unset, unit, range, when, about)
    class(nml_group_t), intent(inout) :: g
    character(len=*), intent(in) :: name
    real(dp), intent(inout), target :: x(:)
    integer, intent(in), optional :: first
    real(dp), intent(in), optional :: unset
    character(len=*), intent(in), optional :: unit, range, when, about
    type(nml_var_t) :: v
    v = new_var(name, 'r', unit, range, when, about)
    call list_shape(v, first, present(unset))
    if (present(unset)) v%unset_real = unset
    v%ra(v%first:) => x
    call append(g, v)
  end subroutine add_real_list

  subroutine add_integer_list(g, name, x, first, unset, unit, range, when, about)
    class(nml_group_t), intent(inout) :: g
    character(len=*), intent(in) :: name
    integer, intent(inout), target :: x(:)
    integer, intent(in), optional :: first, unset
    character(len=*), intent(in), optional :: unit, range, when, about
    type(nml_var_t) :: v
    v = new_var(name, 'i', unit, range, when, about)
    call list_shape(v, first, present(unset))
    if (present(unset)) v%unset_integer = unset
    v%ia(v%first:) => x
    call append(g, v)
  end subroutine add_integer_list

  !> A list of logicals x(first:), every entry a setting.
  subroutine add_logical_list(g, name, x, first, about)
    class(nml_group_t), intent(inout) :: g
    character(len=*), intent(in) :: name
    logical, intent(inout), target :: x(:)
    integer, intent(in), optional :: first
    character(len=*), intent(in), optional :: about
    type(nml_var_t) :: v
    v = new_var(name, 'l', about=about)
    call list_shape(v, first, .false.)
    v%la(v%first:) => x
    call append(g, v)
  end subroutine add_logical_list

  !> A list of texts; entries left '' are not settings.
  subroutine add_text_list(g, name, x, first, about)
    class(nml_group_t), intent(inout) :: g
    character(len=*), intent(in) :: name
    character(len=*), intent(inout), target :: x(:)
    integer, intent(in), optional :: first
    character(len=*), intent(in), optional :: about
    type(nml_var_t) :: v
    integer :: k
    v = new_var(name, 's', about=about)
    call list_shape(v, first, .true.)
    allocate (v%ta(v%first:v%first + size(x) - 1))
    do k = 1, size(x)
      v%ta(v%first + k - 1)%s => x(k)
    end do
    call append(g, v)
  end subroutine add_text_list

  subroutine list_shape(v, first, sparse)
    type(nml_var_t), intent(inout) :: v
    integer, intent(in), optional :: first
    logical, intent(in) :: sparse
    v%list = .true.
    v%sparse = sparse
    if (present(first)) v%first = first
  end subroutine list_shape

  !> The index of variable `name` in the table, 0 if none.
  pure integer function find_var(g, name) result(k)
    class(nml_group_t), intent(in) :: g
    character(len=*), intent(in) :: name
    do k = 1, size(g%vars)
      if (g%vars(k)%name == name) return
    end do
    k = 0
  end function find_var

  !> The entries of the sparse list `name` set from its first one; a later entry set
  !> after an unset one fails `status` (a list is given without gaps).
  integer function list_length(g, name, file, status) result(n)
    class(nml_group_t), intent(in) :: g
    character(len=*), intent(in) :: name, file
    type(status_t), intent(inout) :: status
    integer :: k, j, first, last

    n = 0
    k = g%find(name)
    if (k == 0) then
      call fail(status, '&'//trim(g%name)//' has no list '//name//' (a fault of the program)')
      return
    end if
    associate (v => g%vars(k))
      first = v%first
      last = first - 1
      if (associated(v%ra)) last = ubound(v%ra, 1)
      if (associated(v%ia)) last = ubound(v%ia, 1)
      if (allocated(v%ta)) last = ubound(v%ta, 1)
      do j = first, last
        if (.not. entry_set(v, j)) exit
        n = n + 1
      end do
      do j = first + n + 1, last
        if (entry_set(v, j) .and. status%ok) &
          call fail(status, file//': &'//trim(g%name)//' '//name//'('//itoa(first + n)//') is unset but '// &
                    name//'('//itoa(j)//') = '//entry_text(v, j)//' is set: give the list without gaps')
      end do
    end associate
  end function list_length

  !> Whether entry j of the sparse list `v` is set (a text: not blank).
  pure logical function entry_set(v, j)
    type(nml_var_t), intent(in) :: v
    integer, intent(in) :: j
    entry_set = .false.
    if (associated(v%ra)) entry_set = v%ra(j) /= v%unset_real
    if (associated(v%ia)) entry_set = v%ia(j) /= v%unset_integer
    if (allocated(v%ta)) entry_set = len_trim(v%ta(j)%s) > 0
  end function entry_set

  !> Entry j of the list `v` as a message shows it.
  function entry_text(v, j) result(text)
    type(nml_var_t), intent(in) :: v
    integer, intent(in) :: j
    character(len=:), allocatable :: text
    text = ''
    if (associated(v%ra)) text = fmt_real(v%ra(j))
    if (associated(v%ia)) text = itoa(v%ia(j))
    if (allocated(v%ta)) text = "'"//trim(v%ta(j)%s)//"'"
  end function entry_text

  !> "a, b (real, m), c (integer), ...": the variables with their types and units,
  !> those of one description named together.
  function group_variables(g) result(text)
    class(nml_group_t), intent(in) :: g
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, size(g%vars)
      associate (v => g%vars(k))
        text = text//trim(v%name)
        if (v%list .and. v%sparse .and. v%kind /= 's') text = text//'(j)'
        if (k < size(g%vars)) then
          if (g%vars(k + 1)%about == v%about) then
            text = text//', '
            cycle
          end if
        end if
        text = text//' ('//v%about//')'
        if (k < size(g%vars)) text = text//', '
      end associate
    end do
  end function group_variables

  !> Check each range and choice of the table whose `when` is `when` (default: those
  !> without), in table order; the first value outside fails `status`.
  subroutine check_group(g, file, status, when)
    class(nml_group_t), intent(in) :: g
    character(len=*), intent(in) :: file
    type(status_t), intent(inout) :: status
    character(len=*), intent(in), optional :: when
    integer :: k, j

    do k = 1, size(g%vars)
      if (.not. status%ok) return
      associate (v => g%vars(k))
        if (present(when)) then
          if (v%when /= when) cycle
        else if (v%when /= '') then
          cycle
        end if
        if (.not. v%range%valid) then
          call fail(status, 'the range "'//v%range%text//'" of &'//trim(g%name)//' '//trim(v%name)// &
                    ' cannot be read (a fault of the program)')
          return
        end if
        if (size(v%choices) > 0) then
          if (.not. any(v%choices == lower(v%t))) &
            call fail(status, file//': &'//trim(g%name)//' '//trim(v%name)//" = '"//trim(v%t)// &
                      "' is not one of '"//join_words(v%choices, "', '")//"'")
        end if
        if (len(v%range%text) == 0) cycle
        if (associated(v%r)) then
          if (.not. (v%sparse .and. v%r == v%unset_real)) &
            call need(in_range(v%range, v%r), file, trim(g%name), trim(v%name), v%r, v%range%text, status)
        end if
        if (associated(v%i)) call need(in_range(v%range, real(v%i, dp)), file, trim(g%name), trim(v%name), v%i, &
                                       v%range%text, status)
        if (associated(v%ra)) then
          do j = lbound(v%ra, 1), ubound(v%ra, 1)
            if (v%sparse .and. v%ra(j) == v%unset_real) cycle
            call need(in_range(v%range, v%ra(j)), file, trim(g%name), trim(v%name)//'('//itoa(j)//')', v%ra(j), &
                      v%range%text, status)
          end do
        end if
        if (associated(v%ia)) then
          do j = lbound(v%ia, 1), ubound(v%ia, 1)
            if (v%sparse .and. v%ia(j) == v%unset_integer) cycle
            call need(in_range(v%range, real(v%ia(j), dp)), file, trim(g%name), trim(v%name)//'('//itoa(j)//')', &
                      v%ia(j), v%range%text, status)
          end do
        end if
      end associate
    end do
  end subroutine check_group

  !> The effective settings of the group, in table order (a sparse list: its set entries; a
  !> real with `unset`: where set).
  function group_entries(g) result(e)
    class(nml_group_t), intent(in) :: g
    type(config_entry_t), allocatable :: e(:)
    character(len=:), allocatable :: n
    type(nml_var_t) :: v
    integer :: k, j
    allocate (e(0))
    do k = 1, size(g%vars)
      v = g%vars(k)
      n = trim(v%name)
      associate (group => g%name)
        if (associated(v%r)) then
          if (.not. (v%sparse .and. v%r == v%unset_real)) e = [e, config_entry_t(group, n, v%kind, real_text(v%r))]
        end if
        if (associated(v%i)) e = [e, config_entry_t(group, n, v%kind, itoa(v%i))]
        if (associated(v%l)) e = [e, config_entry_t(group, n, v%kind, merge('.true. ', '.false.', v%l))]
        if (associated(v%la)) then
          do j = lbound(v%la, 1), ubound(v%la, 1)
            e = [e, config_entry_t(group, n//'('//itoa(j)//')', v%kind, merge('.true. ', '.false.', v%la(j)))]
          end do
        end if
        if (associated(v%t)) e = [e, config_entry_t(group, n, v%kind, v%t)]
        if (associated(v%ra)) then
          do j = lbound(v%ra, 1), ubound(v%ra, 1)
            if (v%sparse .and. v%ra(j) == v%unset_real) cycle
            e = [e, config_entry_t(group, n//'('//itoa(j)//')', v%kind, real_text(v%ra(j)))]
          end do
        end if
        if (associated(v%ia)) then
          do j = lbound(v%ia, 1), ubound(v%ia, 1)
            if (v%sparse .and. v%ia(j) == v%unset_integer) cycle
            e = [e, config_entry_t(group, n//'('//itoa(j)//')', v%kind, itoa(v%ia(j)))]
          end do
        end if
        if (allocated(v%ta)) then
          do j = lbound(v%ta, 1), ubound(v%ta, 1)
            if (len_trim(v%ta(j)%s) == 0) cycle
            e = [e, config_entry_t(group, n//'('//itoa(j)//')', v%kind, v%ta(j)%s)]
          end do
        end if
      end associate
    end do
  end function group_entries

  !> A real as the result files record it: 17 significant digits, exact.
  function real_text(x) result(text)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: text
    character(len=32) :: buf
    write (buf, '(es24.16)') x
    text = trim(adjustl(buf))
  end function real_text

end module voussoir_namelist_group
