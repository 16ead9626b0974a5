!> The sweep modes by name: the one place that knows them all. `make_sweep_mode` turns
!> the &sweep `mode` into its type (one file each: src/sweep/sweep_mode_<name>.f90); an
!> unknown name is refused with the list of the known ones. A new mode is one more
!> name here and one more `case`.
module voussoir_sweep_mode_factory
  use voussoir_status, only: status_t, fail
  use voussoir_text, only: lower, join_words
  use voussoir_sweep_mode, only: sweep_mode_t
  use voussoir_sweep_mode_threshold, only: threshold_mode_t
  use voussoir_sweep_mode_grid, only: grid_mode_t
  use voussoir_sweep_mode_ida, only: ida_mode_t
  use voussoir_sweep_mode_msa, only: msa_mode_t
  implicit none
  private

  public :: make_sweep_mode, default_mode, known_modes

  character(len=*), parameter :: threshold_mode = 'threshold'  !! the collapse threshold amplitude per frequency
  character(len=*), parameter :: grid_mode = 'grid'            !! every frequency x amplitude
  character(len=*), parameter :: ida_mode = 'ida'              !! the threshold scale of each record
  character(len=*), parameter :: msa_mode = 'msa'              !! each record scaled to stated levels
  !> The modes, in the order the error message lists them.
  character(len=16), parameter :: known_modes(4) = [character(len=16) :: threshold_mode, grid_mode, ida_mode, msa_mode]
  !> The mode of a &sweep group that gives none.
  character(len=*), parameter :: default_mode = threshold_mode

contains

  !> The mode named `name` (any case), or a failed `status` naming `path` and the modes.
  subroutine make_sweep_mode(path, name, mode, status)
    character(len=*), intent(in) :: path, name
    class(sweep_mode_t), allocatable, intent(out) :: mode
    type(status_t), intent(inout) :: status
    select case (lower(name))
    case (threshold_mode)
      allocate (threshold_mode_t :: mode)
    case (grid_mode)
      allocate (grid_mode_t :: mode)
    case (ida_mode)
      allocate (ida_mode_t :: mode)
    case (msa_mode)
      allocate (msa_mode_t :: mode)
    case default
      call fail(status, path//": &sweep mode = '"//trim(name)//"' is not one of '"// &
                join_words(known_modes, "', '")//"'")
      return
    end select
    mode%name = lower(name)
  end subroutine make_sweep_mode

end module voussoir_sweep_mode_factory
