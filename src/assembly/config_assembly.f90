!> The assembly a validated configuration describes: a &wall, a polygon file, or the arch
!> builder (with its restraint brackets and size imperfections). voussoir-run's set-up
!> and voussoir-limit build it here, so both analyse the same blocks.
module voussoir_config_assembly
  use voussoir_status, only: status_t
  use voussoir_config, only: config_t, springings_left, springings_right, springings_both
  use voussoir_assembly, only: assembly_t, build_arch, voussoir_angle_factors
  use voussoir_polygon_file, only: read_polygon_file
  use voussoir_wall, only: build_wall
  use voussoir_bridge, only: build_bridge
  implicit none
  private
  public :: build_config_assembly

contains

  !> The bridge of cfg%bridge where it has spans, the wall of cfg%wall where it has courses,
  !> else the polygon file of &arch where one is named (its message then starts with
  !> '&arch polygon_file: '), else the arch of &arch.
  subroutine build_config_assembly(cfg, assembly, status)
    type(config_t), intent(in) :: cfg
    type(assembly_t), intent(out) :: assembly
    type(status_t), intent(inout) :: status
    logical :: restrained(2)
    associate (a => cfg%arch)
      if (cfg%bridge%n_spans > 0) then
        call build_bridge(cfg%bridge, assembly, status)
      else if (cfg%wall%courses > 0) then
        call build_wall(cfg%wall, assembly)
      else if (len_trim(a%polygon_file) > 0) then
        call read_polygon_file(trim(a%polygon_file), assembly, status)
        if (.not. status%ok) then
          status%message = '&arch polygon_file: '//trim(status%message)
          return
        end if
        assembly%thickness_m = a%thickness_m
      else
        restrained = [a%restrained_springings == springings_left .or. a%restrained_springings == springings_both, &
                      a%restrained_springings == springings_right .or. a%restrained_springings == springings_both]
        call build_arch(a%embrace_deg, a%n_voussoirs, a%r_ext_m, a%thickness_m, assembly, restrained, &
                        voussoir_angle_factors(a%n_voussoirs, a%size_imperfection, a%imperfection_seed), &
                        a%bracket_gap_m)
      end if
    end associate
  end subroutine build_config_assembly

end module voussoir_config_assembly
