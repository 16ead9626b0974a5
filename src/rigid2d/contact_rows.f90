!> The layout of the packed per-contact data of the contact solve (`nlgs_work_t%data`),
!> shared by the Gauss-Seidel sweeps and the coarse correction.
module voussoir_contact_rows
  use voussoir_kinds, only: dp
  implicit none
  private

  public :: apply_impulse_change

  ! Rows of the packed per-contact data: tangent, normal, cross(arm, t or n) of bodies a
  ! and b, the Delassus block and its determinant, the gap shift max(0, gap)/(theta h)
  ! [m/s], the friction coefficient and the inverse masses and inertias of a and b.
  integer, parameter, public :: i_t = 1, i_n = 3, i_arm_at = 5, i_arm_an = 6, i_arm_bt = 7, &
                                i_arm_bn = 8, i_w_tt = 9, i_w_tn = 10, i_w_nn = 11, i_det = 12, &
                                i_shift = 13, i_mu = 14, i_ima = 15, i_iia = 16, i_imb = 17, &
                                i_iib = 18, n_rows = 18

contains

  !> The velocities `va`, `vb` (3) of a contact's bodies a and b after a change (dr_t, dr_n)
  !> [N s] of its impulse, from its packed column `c`: v_a + M_a^-1 H_a^T dr and
  !> v_b - M_b^-1 H_b^T dr. (The sweep writes the same operations inline, to keep the
  !> velocities in registers from one contact to the next.)
  pure subroutine apply_impulse_change(c, dr_t, dr_n, va, vb)
    real(dp), intent(in) :: c(n_rows), dr_t, dr_n
    real(dp), intent(inout) :: va(3), vb(3)
    real(dp) :: px, py
    px = dr_t*c(i_t) + dr_n*c(i_n)
    py = dr_t*c(i_t + 1) + dr_n*c(i_n + 1)
    va(1) = va(1) + c(i_ima)*px
    va(2) = va(2) + c(i_ima)*py
    va(3) = va(3) + c(i_iia)*(dr_t*c(i_arm_at) + dr_n*c(i_arm_an))
    vb(1) = vb(1) - c(i_imb)*px
    vb(2) = vb(2) - c(i_imb)*py
    vb(3) = vb(3) - c(i_iib)*(dr_t*c(i_arm_bt) + dr_n*c(i_arm_bn))
  end subroutine apply_impulse_change

end module voussoir_contact_rows
