!> The read of a namelist group into its table (voussoir_namelist_group's read): each
!> value converted as gfortran's namelist read converts it (an internal list-directed
!> read, the same conversion), each refusal naming the file, line, variable, what it
!> expects and what it got.
submodule (voussoir_namelist_group) voussoir_namelist_group_read
  implicit none

contains

  module subroutine read_group(g, path, status, found)
    class(nml_group_t), intent(in) :: g
    character(len=*), intent(in) :: path
    type(status_t), intent(inout) :: status
    logical, intent(out), optional :: found
    type(nml_assignment_t), allocatable :: assignments(:)
    logical :: in_file
    integer :: k

    call read_group_text(path, trim(g%name), in_file, assignments, status)
    if (present(found)) found = in_file
    do k = 1, size(assignments)
      if (.not. status%ok) return
      call assign(g, path, assignments(k), status)
    end do
  end subroutine read_group

  !> Store the values of one `name = values` in the variable's target.
  subroutine assign(g, path, a, status)
    class(nml_group_t), intent(in) :: g
    character(len=*), intent(in) :: path
    type(nml_assignment_t), intent(in) :: a
    type(status_t), intent(inout) :: status
    character(len=:), allocatable :: at
    integer :: k, n, pos, first, last, j

    at = path//':'//itoa(a%line)//': &'//trim(g%name)
    k = g%find(a%name)
    if (k == 0) then
      call fail(status, at//" has no variable '"//a%name//"' (known: "//join_words(g%vars%name)//')')
      return
    end if
    n = 0
    do j = 1, size(a%values)
      if (a%values(j)%repeat < 1) then
        call fail(status, at//' '//a%written//' = '//a%values(j)%text//': a repeat count r*value needs r >= 1')
        return
      end if
      n = n + a%values(j)%repeat
    end do
    associate (v => g%vars(k))
      if (a%indexed .and. .not. v%list) then
        call fail(status, at//' '//a%written//': '//trim(v%name)//' is one value, not a list (write '// &
                  trim(v%name)//' = value)')
        return
      end if
      ! Past the list's end first: the clearer refusal of an element given several values.
      first = v%first
      last = first + list_size(v) - 1
      pos = merge(a%index, first, a%indexed)
      if (v%list .and. pos < first) then
        call fail(status, at//' '//a%written//': the entries of '//trim(v%name)//' are '//itoa(first)//' to '// &
                  itoa(last))
        return
      else if (v%list .and. pos + n - 1 > last .and. .not. a%indexed) then
        call fail(status, at//' '//trim(v%name)//' has '//itoa(n)//' values; at most '//itoa(last - first + 1))
        return
      else if (v%list .and. pos + n - 1 > last) then
        call fail(status, at//' '//trim(v%name)//' has values up to entry '//itoa(pos + n - 1)//'; at most '// &
                  itoa(last))
        return
      end if
      if ((a%indexed .or. .not. v%list) .and. n > 1) then
        call fail(status, at//' '//a%written//' takes one value; it is given '//itoa(n))
        return
      end if
      do j = 1, size(a%values)
        associate (value => a%values(j))
          if (.not. value%null) call store(g, k, pos, value%repeat, value%text, at, status)
          if (.not. status%ok) return
          pos = pos + value%repeat
        end associate
      end do
    end associate
  end subroutine assign

  pure integer function list_size(v)
    type(nml_var_t), intent(in) :: v
    list_size = 1
    if (associated(v%ra)) list_size = size(v%ra)
    if (associated(v%ia)) list_size = size(v%ia)
    if (associated(v%la)) list_size = size(v%la)
    if (allocated(v%ta)) list_size = size(v%ta)
  end function list_size

  !> Convert `text` for variable k of `g` and store it `repeat` times from entry `pos`.
  subroutine store(g, k, pos, repeat, text, at, status)
    class(nml_group_t), intent(in) :: g
    integer, intent(in) :: k, pos, repeat
    character(len=*), intent(in) :: text, at
    type(status_t), intent(inout) :: status
    real(dp) :: x
    integer :: m, ios
    logical :: b
    character(len=:), allocatable :: name, s
    type(nml_var_t) :: v

    v = g%vars(k)   ! a copy of the entry points at the same targets
    name = trim(v%name)
    if (v%list) name = name//'('//itoa(pos)//')'
    ios = 1
    if (v%kind == 's') then
      if (quoted(text)) then
        s = unquoted(text)
        ios = 0
      end if
    else if (.not. quoted(text)) then
      select case (v%kind)
      case ('r')
        read (text, *, iostat=ios) x
      case ('i')
        read (text, *, iostat=ios) m
      case ('l')
        read (text, *, iostat=ios) b
      end select
    end if
    if (ios /= 0) then
      call fail(status, at//' '//name//' = '//text//' is not '//expected(v%kind, trim(v%name), text)// &
                '. The variables of &'//trim(g%name)//' are: '//g%variables())
      return
    end if
    if (associated(v%r)) v%r = x
    if (associated(v%i)) v%i = m
    if (associated(v%l)) v%l = b
    if (associated(v%t)) v%t = choice_case(v, s)
    if (associated(v%ra)) v%ra(pos:pos + repeat - 1) = x
    if (associated(v%ia)) v%ia(pos:pos + repeat - 1) = m
    if (associated(v%la)) v%la(pos:pos + repeat - 1) = b
    if (allocated(v%ta)) then
      do m = pos, pos + repeat - 1
        v%ta(m)%s = s
      end do
    end if
  end subroutine store

  !> What a value of `kind` must look like.
  function expected(kind, name, text) result(words)
    character(len=*), intent(in) :: kind, name, text
    character(len=:), allocatable :: words
    select case (kind)
    case ('r')
      words = 'a number (e.g. 0.5, -2 or 1e-3)'
    case ('i')
      words = 'a whole number (an integer from -'//itoa(huge(1))//' to '//itoa(huge(1))//')'
    case ('l')
      words = 'a logical (.true. or .false.)'
    case default
      words = "a text in quotes (write "//name//" = '"//text//"')"
    end select
  end function expected

  pure logical function quoted(text)
    character(len=*), intent(in) :: text
    quoted = .false.
    if (len(text) < 2) return
    quoted = (text(1:1) == "'" .or. text(1:1) == '"') .and. text(len(text):) == text(1:1)
  end function quoted

  !> The text between the quotes, a doubled quote read as one.
  pure function unquoted(text) result(s)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    i = 2
    do while (i < len(text))
      s = s//text(i:i)
      if (text(i:i) == text(1:1)) i = i + 1
      i = i + 1
    end do
  end function unquoted

  !> A choice is read in any case and kept in lower case; another text as written.
  pure function choice_case(v, s) result(t)
    type(nml_var_t), intent(in) :: v
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: t
    t = s
    if (size(v%choices) > 0) t = lower(s)
  end function choice_case

end submodule voussoir_namelist_group_read
