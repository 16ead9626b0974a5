!> The LP time of the limit analysis of any assembly (bench/limit_lp.sh builds and runs it):
!> a 20-block ring, a 10 x 10 wall and a 40 x 50 wall (2,000 blocks).
program bench_limit_lp
  use voussoir_kinds, only: dp
  use voussoir_status, only: status_t
  use voussoir_assembly, only: assembly_t, build_arch
  use voussoir_wall_config, only: wall_config_t
  use voussoir_wall, only: build_wall
  use voussoir_block_interfaces, only: interface_set_t, find_interfaces
  use voussoir_limit_lp, only: block_loads_t, lp_result_t, block_loads, lp_capacity
  implicit none
  type(assembly_t) :: asm
  type(wall_config_t) :: w
  call build_arch(180.0_dp, 20, 1.0_dp, 0.12_dp, asm)
  call time_one('ring of 20 voussoirs (180 deg)', asm)
  w%courses = 10
  w%blocks_per_course = 10
  w%bond = 'stack'
  call build_wall(w, asm)
  call time_one('wall 10 x 10 (stack bond)', asm)
  w%courses = 50
  w%blocks_per_course = 40
  call build_wall(w, asm)
  call time_one('wall 40 x 50 = 2000 blocks (stack bond)', asm)
contains
  subroutine time_one(name, asm)
    character(len=*), intent(in) :: name
    type(assembly_t), intent(in) :: asm
    type(interface_set_t) :: faces
    type(block_loads_t) :: loads
    type(lp_result_t) :: res
    type(status_t) :: status
    integer(8) :: t0, t1, t2, rate
    call system_clock(t0, rate)
    call find_interfaces(asm, 1.0e-9_dp, 0.0_dp, faces, status)
    call block_loads(asm, 2000.0_dp, 1.0_dp, 9.81_dp, loads)
    call system_clock(t1)
    call lp_capacity(asm, faces, loads, spread(0.6_dp, 1, faces%n), spread(0.0_dp, 1, faces%n), res, status)
    call system_clock(t2)
    write (*, '(a45,i6,a,i6,a,f9.4,a,f9.4,a,f10.6,1x,a)') name, asm%n_bodies, ' blocks', faces%n, ' interfaces  LP ', &
      real(t2 - t1)/rate, ' s  interfaces ', real(t1 - t0)/rate, ' s  lambda ', res%load_factor, trim(status%message)
  end subroutine time_one
end program bench_limit_lp
