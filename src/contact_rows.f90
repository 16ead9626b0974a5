!> The layout of the packed per-contact data of the contact solve (`nlgs_work_t%data`),
!> shared by the Gauss-Seidel sweeps and the coarse correction.
module voussoir_contact_rows
  implicit none
  private

  ! Rows of the packed per-contact data: tangent, normal, cross(arm, t or n) of bodies a
  ! and b, the Delassus block and its determinant, the gap shift max(0, gap)/(theta h)
  ! [m/s], the friction coefficient and the inverse masses and inertias of a and b.
  integer, parameter, public :: i_t = 1, i_n = 3, i_arm_at = 5, i_arm_an = 6, i_arm_bt = 7, &
                                i_arm_bn = 8, i_w_tt = 9, i_w_tn = 10, i_w_nn = 11, i_det = 12, &
                                i_shift = 13, i_mu = 14, i_ima = 15, i_iia = 16, i_imb = 17, &
                                i_iib = 18, n_rows = 18

end module voussoir_contact_rows
