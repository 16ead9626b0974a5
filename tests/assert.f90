!> A small assertion module for the CTest programs (stands in for pFUnit).
!>
!> Each test program calls the checks, then `assert_summary`, which prints
!> 'N passed, N failed' and stops with a non-zero code if any check failed.
module voussoir_assert
  use voussoir_kinds, only: dp
  implicit none
  private

  public :: assert_true, assert_close, assert_summary

  integer, save :: n_passed = 0, n_failed = 0

contains

  !> Check that `condition` holds.
  subroutine assert_true(condition, name)
    logical, intent(in) :: condition
    character(len=*), intent(in) :: name
    if (condition) then
      n_passed = n_passed + 1
      write (*, '(a)') 'PASS  '//name
    else
      n_failed = n_failed + 1
      write (*, '(a)') 'FAIL  '//name
    end if
  end subroutine assert_true

  !> Check |actual - expected| <= atol + rtol |expected|.
  subroutine assert_close(actual, expected, name, rtol, atol)
    real(dp), intent(in) :: actual, expected
    character(len=*), intent(in) :: name
    real(dp), intent(in), optional :: rtol, atol
    real(dp) :: rt, at
    logical :: good
    rt = 0.0_dp
    at = 0.0_dp
    if (present(rtol)) rt = rtol
    if (present(atol)) at = atol
    good = abs(actual - expected) <= at + rt*abs(expected)
    if (good) then
      n_passed = n_passed + 1
    else
      n_failed = n_failed + 1
    end if
    write (*, '(a,a,a,es16.8,a,es16.8,a,es10.3)') merge('PASS  ', 'FAIL  ', good), name, &
      ': got ', actual, ' expected ', expected, ' rel.err ', &
      abs(actual - expected)/max(abs(expected), tiny(1.0_dp))
  end subroutine assert_close

  !> Print the closing line and fail the program if any check failed.
  subroutine assert_summary()
    write (*, '(i0,a,i0,a)') n_passed, ' passed, ', n_failed, ' failed'
    if (n_failed > 0) error stop 1
    if (n_passed == 0) error stop 'no check was run'
  end subroutine assert_summary

end module voussoir_assert
