!> GLPK's C interface (Debian libglpk-dev) bound with iso_c_binding, and one stateless
!> call that builds a linear programme, maximises it by the (scaled, primal) simplex method,
!> and frees it. The kernel's only linear-programming solver: no simplex of our own.
module voussoir_glpk
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double
  use voussoir_kinds, only: dp
  implicit none
  private

  public :: lp_solve, lp_free, lp_lower, lp_upper, lp_double, lp_fixed
  public :: lp_optimal, lp_infeasible, lp_unbounded, lp_failed

  ! Bound types of glpk.h.
  integer, parameter :: lp_free = 1, lp_lower = 2, lp_upper = 3, lp_double = 4, lp_fixed = 5
  ! Outcomes of lp_solve.
  integer, parameter :: lp_optimal = 0, lp_infeasible = 1, lp_unbounded = 2, lp_failed = 3

  integer(c_int), parameter :: glp_max = 2, glp_opt = 5, glp_nofeas = 4, glp_unbnd = 6
  integer(c_int), parameter :: glp_enopfs = 10, glp_enodfs = 11

  interface
    type(c_ptr) function glp_create_prob() bind(c, name='glp_create_prob')
      import :: c_ptr
    end function glp_create_prob
    subroutine glp_delete_prob(p) bind(c, name='glp_delete_prob')
      import :: c_ptr
      type(c_ptr), value :: p
    end subroutine glp_delete_prob
    subroutine glp_set_obj_dir(p, dir) bind(c, name='glp_set_obj_dir')
      import :: c_ptr, c_int
      type(c_ptr), value :: p
      integer(c_int), value :: dir
    end subroutine glp_set_obj_dir
    integer(c_int) function glp_add_rows(p, n) bind(c, name='glp_add_rows')
      import :: c_ptr, c_int
      type(c_ptr), value :: p
      integer(c_int), value :: n
    end function glp_add_rows
    integer(c_int) function glp_add_cols(p, n) bind(c, name='glp_add_cols')
      import :: c_ptr, c_int
      type(c_ptr), value :: p
      integer(c_int), value :: n
    end function glp_add_cols
    subroutine glp_set_row_bnds(p, i, kind, lb, ub) bind(c, name='glp_set_row_bnds')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: p
      integer(c_int), value :: i, kind
      real(c_double), value :: lb, ub
    end subroutine glp_set_row_bnds
    subroutine glp_set_col_bnds(p, j, kind, lb, ub) bind(c, name='glp_set_col_bnds')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: p
      integer(c_int), value :: j, kind
      real(c_double), value :: lb, ub
    end subroutine glp_set_col_bnds
    subroutine glp_set_obj_coef(p, j, coef) bind(c, name='glp_set_obj_coef')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: p
      integer(c_int), value :: j
      real(c_double), value :: coef
    end subroutine glp_set_obj_coef
    subroutine glp_load_matrix(p, ne, ia, ja, ar) bind(c, name='glp_load_matrix')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: p
      integer(c_int), value :: ne
      integer(c_int), intent(in) :: ia(*), ja(*)   ! 1-based, element 0 unused
      real(c_double), intent(in) :: ar(*)
    end subroutine glp_load_matrix
    integer(c_int) function voussoir_glpk_simplex(p, presolve) bind(c, name='voussoir_glpk_simplex')
      import :: c_ptr, c_int
      type(c_ptr), value :: p
      integer(c_int), value :: presolve
    end function voussoir_glpk_simplex
    integer(c_int) function glp_get_status(p) bind(c, name='glp_get_status')
      import :: c_ptr, c_int
      type(c_ptr), value :: p
    end function glp_get_status
    real(c_double) function glp_get_obj_val(p) bind(c, name='glp_get_obj_val')
      import :: c_ptr, c_double
      type(c_ptr), value :: p
    end function glp_get_obj_val
    real(c_double) function glp_get_col_prim(p, j) bind(c, name='glp_get_col_prim')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: p
      integer(c_int), value :: j
    end function glp_get_col_prim
    real(c_double) function glp_get_row_dual(p, i) bind(c, name='glp_get_row_dual')
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: p
      integer(c_int), value :: i
    end function glp_get_row_dual
    integer(c_int) function glp_get_unbnd_ray(p) bind(c, name='glp_get_unbnd_ray')
      import :: c_ptr, c_int
      type(c_ptr), value :: p
    end function glp_get_unbnd_ray
  end interface

contains

  !> Maximise obj . x subject to row_lo <= A x <= row_hi (row_kind) and col_lo <= x <=
  !> col_hi (col_kind), A given by its nonzeros (ia, ja, ar). On lp_optimal: x, the row
  !> duals and the objective. On lp_unbounded: ray_col, the column (0 if a row or
  !> unknown) along which the objective grows without bound.
  subroutine lp_solve(row_kind, row_lo, row_hi, col_kind, col_lo, col_hi, obj, ia, ja, ar, &
                      x, row_dual, objective, outcome, ray_col)
    integer, intent(in) :: row_kind(:), col_kind(:), ia(:), ja(:)
    real(dp), intent(in) :: row_lo(:), row_hi(:), col_lo(:), col_hi(:), obj(:), ar(:)
    real(dp), intent(out) :: x(size(col_kind)), row_dual(size(row_kind)), objective
    integer, intent(out) :: outcome, ray_col
    type(c_ptr) :: p
    integer(c_int) :: rc, first, k, m, n, ray
    integer(c_int), allocatable :: cia(:), cja(:)
    real(c_double), allocatable :: car(:)

    m = size(row_kind)
    n = size(col_kind)
    x = 0.0_dp
    row_dual = 0.0_dp
    objective = 0.0_dp
    ray_col = 0
    p = glp_create_prob()
    call glp_set_obj_dir(p, glp_max)
    first = glp_add_rows(p, m)
    first = glp_add_cols(p, n)
    do k = 1, m
      call glp_set_row_bnds(p, k, int(row_kind(k), c_int), real(row_lo(k), c_double), real(row_hi(k), c_double))
    end do
    do k = 1, n
      call glp_set_col_bnds(p, k, int(col_kind(k), c_int), real(col_lo(k), c_double), real(col_hi(k), c_double))
      call glp_set_obj_coef(p, k, real(obj(k), c_double))
    end do
    allocate (cia(0:size(ia)), cja(0:size(ia)), car(0:size(ia)))
    cia(0) = 0
    cja(0) = 0
    car(0) = 0.0_c_double
    cia(1:) = int(ia, c_int)
    cja(1:) = int(ja, c_int)
    car(1:) = real(ar, c_double)
    call glp_load_matrix(p, int(size(ia), c_int), cia, cja, car)

    ! No presolve: on the 2,000-block wall of bench/limit_lp.sh it made the solve 14 times
    ! slower (94 s against 7 s), and it keeps no unbounded ray to name a block by
    ! (docs/limit_analysis.md, "GLPK").
    rc = voussoir_glpk_simplex(p, 0_c_int)
    if (rc == glp_enopfs) then
      outcome = lp_infeasible
    else if (rc /= 0) then
      outcome = lp_failed
    else
      select case (glp_get_status(p))
      case (glp_opt)
        outcome = lp_optimal
        objective = glp_get_obj_val(p)
        do k = 1, n
          x(k) = glp_get_col_prim(p, k)
        end do
        do k = 1, m
          row_dual(k) = glp_get_row_dual(p, k)
        end do
      case (glp_nofeas)
        outcome = lp_infeasible
      case (glp_unbnd)
        outcome = lp_unbounded
        ray = glp_get_unbnd_ray(p)
        if (ray > m) ray_col = ray - m
      case default
        outcome = lp_failed
      end select
    end if
    call glp_delete_prob(p)
  end subroutine lp_solve

end module voussoir_glpk
