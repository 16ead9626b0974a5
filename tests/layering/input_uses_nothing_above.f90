!> A probe of the layering, never part of a program: a module of the input layer that
!> uses a module of the run layer above it. tests/layering.cmake builds it twice: linked
!> to the input layer alone it must not compile (the run layer's modules are not in its
!> path), linked to the run layer it must (so the failure is the layering's, not a typo).
module voussoir_layering_probe
  use voussoir_config, only: config_t
  use voussoir_setup, only: run_config
  implicit none
  private
  public :: probe
contains
  subroutine probe(cfg)
    type(config_t), intent(in) :: cfg
    if (.false.) print *, cfg%output%file
  end subroutine probe
end module voussoir_layering_probe
