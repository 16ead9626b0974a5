!> A run that the user stops (Ctrl-C, SIGINT, or SIGTERM from a batch system) ends at
!> the next step, and its driver writes what was computed, marked interrupted. The
!> signal is recorded by a C handler (interrupt.c); nothing happens unless a driver
!> asked for it with `catch_stop_signals`.
module voussoir_interrupt
  use, intrinsic :: iso_c_binding, only: c_int
  implicit none
  private
  public :: catch_stop_signals, stop_signal

  interface
    function c_catch() bind(C, name='voussoir_catch_stop_signals') result(rc)
      import :: c_int
      integer(c_int) :: rc
    end function c_catch
    function c_signal() bind(C, name='voussoir_stop_signal') result(sig)
      import :: c_int
      integer(c_int) :: sig
    end function c_signal
  end interface

contains

  !> Catch SIGINT and SIGTERM from now on; false if the handlers could not be set.
  logical function catch_stop_signals()
    catch_stop_signals = c_catch() == 0
  end function catch_stop_signals

  !> The signal that asked the run to stop (0: none).
  integer function stop_signal()
    stop_signal = int(c_signal())
  end function stop_signal

end module voussoir_interrupt
