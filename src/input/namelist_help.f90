!> The namelist groups a driver reads, as its `--help` lists them: walked from the group
!> tables (voussoir_namelist_group) that the read and the range checks use, so the list
!> names every variable with its type, unit, default and allowed range or choices, and
!> cannot disagree with what the program reads. Nothing here is written by hand.
module voussoir_namelist_help
  use voussoir_kinds, only: dp
  use voussoir_text, only: itoa, fmt_real
  use voussoir_namelist_group, only: nml_group_t, checked_apart
  implicit none
  private

  public :: groups_help

  character(len=1), parameter :: nl = achar(10)

contains

  !> One block per group: a line `&name`, then one line per variable of its table,
  !> `  name = default   type, unit; range (case it applies to)`. A list shows as
  !> `name(j)` with its indices; a list entry left unset shows `unset`.
  function groups_help(groups) result(text)
    type(nml_group_t), intent(in) :: groups(:)
    character(len=:), allocatable :: text
    character(len=:), allocatable :: left
    integer :: k, v, width

    width = 0
    do k = 1, size(groups)
      do v = 1, size(groups(k)%vars)
        width = max(width, len(name_default(groups(k), v)))
      end do
    end do
    text = 'Namelist groups of FILE.nml (every variable with its default, type, unit and allowed range; '// &
           'a range marked (only ...) is checked in that case only):'
    do k = 1, size(groups)
      text = text//nl//nl//'&'//trim(groups(k)%name)
      do v = 1, size(groups(k)%vars)
        left = name_default(groups(k), v)
        text = text//nl//left//repeat(' ', width - len(left) + 2)//description(groups(k), v)
      end do
    end do
  end function groups_help

  !> `  name = default` of variable v of group g (`name(j)` for a list).
  function name_default(g, v) result(text)
    type(nml_group_t), intent(in) :: g
    integer, intent(in) :: v
    character(len=:), allocatable :: text
    associate (x => g%vars(v))
      text = '  '//trim(x%name)
      if (x%list) text = text//'(j)'
      text = text//' = '//default_text(g, v)
    end associate
  end function name_default

  !> The default of variable v as the table holds it now (the tables are built over a
  !> default configuration): a list shows its first entry, or `unset` for a sparse one.
  function default_text(g, v) result(text)
    type(nml_group_t), intent(in) :: g
    integer, intent(in) :: v
    character(len=:), allocatable :: text
    text = ''
    associate (x => g%vars(v))
      if (associated(x%r)) text = real_default(x%r)
      if (associated(x%i)) text = itoa(x%i)
      if (associated(x%l)) text = trim(merge('.true. ', '.false.', x%l))
      if (associated(x%t)) text = "'"//trim(x%t)//"'"
      if (x%sparse) then
        text = 'unset'
      else if (associated(x%ra)) then
        text = real_default(x%ra(lbound(x%ra, 1)))
      else if (associated(x%ia)) then
        text = itoa(x%ia(lbound(x%ia, 1)))
      else if (associated(x%la)) then
        text = trim(merge('.true. ', '.false.', x%la(lbound(x%la, 1))))
      end if
    end associate
  end function default_text

  !> A real default; the sentinel of a value that another one stands in for: `unset`.
  function real_default(x) result(text)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: text
    if (abs(x) >= huge(x)) then
      text = 'unset'
    else
      text = fmt_real(x)
    end if
  end function real_default

  !> `type, unit; range (only case)` of variable v, and a list's indices.
  function description(g, v) result(text)
    type(nml_group_t), intent(in) :: g
    integer, intent(in) :: v
    character(len=:), allocatable :: text
    integer :: last
    associate (x => g%vars(v))
      text = x%about
      if (len(x%range%text) > 0) text = text//'; '//x%range%text
      if (x%when == checked_apart) then
        text = text//' (and against the other variables)'
      else if (len(x%when) > 0) then
        text = text//' (only '//case_text(g, x%when)//')'
      end if
      if (x%list) then
        last = x%first - 1
        if (associated(x%ra)) last = ubound(x%ra, 1)
        if (associated(x%ia)) last = ubound(x%ia, 1)
        if (associated(x%la)) last = ubound(x%la, 1)
        if (allocated(x%ta)) last = ubound(x%ta, 1)
        text = text//'; a list, j = '//itoa(x%first)//'..'//itoa(last)
      end if
    end associate
  end function description

  !> The case `when` of a range in words: `with waveform = 'afd'` where it is a choice of
  !> a variable of the group, else `for <when>` (the arch builder, a polygon file).
  function case_text(g, when) result(text)
    type(nml_group_t), intent(in) :: g
    character(len=*), intent(in) :: when
    character(len=:), allocatable :: text
    integer :: k
    do k = 1, size(g%vars)
      if (any(g%vars(k)%choices == when)) then
        text = 'with '//trim(g%vars(k)%name)//" = '"//trim(when)//"'"
        return
      end if
    end do
    text = 'for '//trim(when)
  end function case_text

end module voussoir_namelist_help
