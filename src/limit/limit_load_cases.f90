!> The load cases of &load_cases in the limit analysis: each case's LP study with its
!> factored loads (the live ones times gamma_q, every permanent one times gamma_g: the
!> blocks' weights, the fill's weight and pressure, the dead loads of &load), the load
!> factor then the multiple of the factored live loads that brings the assembly down, the
!> factored dead loads held fixed: the adequacy factor of an assessment (at least 1: the
!> bridge carries the factored loads). The governing case is the least of them.
!> docs/bridges.md, "Load cases and partial factors".
module voussoir_limit_load_cases
  use voussoir_kinds, only: dp
  use voussoir_assembly, only: assembly_t
  use voussoir_load_config, only: load_config_t
  use voussoir_limit_lp_study, only: lp_study_t
  implicit none
  private
  public :: case_study_t, factored_assembly, governing_case, live_total_n

  !> One load case as analysed.
  type :: case_study_t
    character(len=32) :: name = ''
    real(dp) :: gamma_q = 1.0_dp, gamma_g = 1.0_dp
    real(dp) :: live_total_n = 0.0_dp    !! the factored live loads at load factor 1, summed [N]
    type(lp_study_t) :: lp               !! its LP study (at its critical position on a path)
  end type case_study_t

contains

  !> `asm` with every permanent load it carries times `gamma_g`: the blocks' densities (a
  !> bridge's parts) and the fill's unit weight (its weight and its pressure follow it).
  pure function factored_assembly(asm, gamma_g) result(f)
    type(assembly_t), intent(in) :: asm
    real(dp), intent(in) :: gamma_g
    type(assembly_t) :: f
    f = asm
    if (allocated(f%density_kg_m3)) f%density_kg_m3 = gamma_g*asm%density_kg_m3
    f%fill_weight_n_m2 = gamma_g*asm%fill_weight_n_m2
  end function factored_assembly

  !> The sum of the magnitudes of the live point loads of `d`, each axle of an axle group
  !> counted [N].
  pure real(dp) function live_total_n(d)
    type(load_config_t), intent(in) :: d
    live_total_n = (d%n_axles + 1)*sum(d%point_load_n(1:d%n_point_loads), mask=d%point_load_live(1:d%n_point_loads))
  end function live_total_n

  !> The case of least associative load factor among those solved (the first of equal
  !> ones to 1e-9); 0 if none is.
  pure integer function governing_case(cases) result(k)
    type(case_study_t), intent(in) :: cases(:)
    integer :: i
    k = 0
    do i = 1, size(cases)
      if (.not. cases(i)%lp%solved) cycle
      if (k == 0) then
        k = i
      else if (cases(i)%lp%assoc%load_factor < cases(k)%lp%assoc%load_factor*(1.0_dp - 1.0e-9_dp)) then
        k = i
      end if
    end do
  end function governing_case

end module voussoir_limit_load_cases
