!> The two edges of a joint that a hinge can pivot on: one numbering for the whole code.
!>
!> In memory a side is 1 (intrados) or 2 (extrados), usable as an array index; result
!> files store `side_file_code` (0 intrados, 1 extrados: docs/results_format.md) and the
!> limit JSON the names.
module voussoir_hinge_side
  implicit none
  private

  public :: side_intrados, side_extrados, side_name, side_file_code

  integer, parameter :: side_intrados = 1  !! hinge on the intrados (inner) edge of a joint
  integer, parameter :: side_extrados = 2  !! hinge on the extrados (outer) edge of a joint

contains

  !> 'intrados' or 'extrados'.
  pure function side_name(side) result(name)
    integer, intent(in) :: side
    character(len=:), allocatable :: name
    if (side == side_intrados) then
      name = 'intrados'
    else
      name = 'extrados'
    end if
  end function side_name

  !> The code of a side in result files: 0 intrados, 1 extrados.
  elemental integer function side_file_code(side)
    integer, intent(in) :: side
    side_file_code = side - side_intrados
  end function side_file_code

end module voussoir_hinge_side
