! voxspan.f90 - Fortran 2003 bindings (iso_c_binding) of the C API in voxspan/voxspan.h.
! Compile this file with the solver and link libvoxspan. Every call returns VOXSPAN_OK or an
! error code; voxspan_error_message() gives the message. Arrays are passed with c_loc():
!
!   use voxspan
!   type(voxspan_adapter_options) :: opt
!   type(c_ptr) :: adapter, particles
!   call voxspan_adapter_options_init(opt)
!   opt%render_every = 10; opt%particle_spacing = dx
!   adapter = voxspan_adapter_create(opt)
!   particles = voxspan_particles_create()
!   rc = voxspan_particles_set_soa(particles, VOXSPAN_FLOAT64, c_loc(x), c_loc(y), c_loc(z), n)
!   rc = voxspan_adapter_execute(adapter, step, time, particles, c_null_ptr)
!
! The arrays must be TARGETs and stay in place until the execute call that uses them returns.
! Grid indices may be 1-based: voxspan_grid_set_index_base(grid, 1). Names and paths are
! NUL-terminated: "velocity" // c_null_char. Every function of voxspan.h is bound here
! (tests/cli/fortran_bindings_check.sh holds it so); link the compiled module with the solver.
module voxspan
  use, intrinsic :: iso_c_binding
  implicit none

  integer(c_int), parameter :: VOXSPAN_OK = 0, VOXSPAN_INVALID_INPUT = 1, &
                               VOXSPAN_PIPELINE_FAILED = 2, VOXSPAN_INTERNAL_ERROR = 3
  integer(c_int), parameter :: VOXSPAN_FLOAT32 = 0, VOXSPAN_FLOAT64 = 1
  integer(c_int), parameter :: VOXSPAN_INT32 = 0, VOXSPAN_UINT32 = 1, VOXSPAN_INT64 = 2, &
                               VOXSPAN_UINT64 = 3

  type, bind(C) :: voxspan_adapter_options
    integer(c_int64_t) :: render_every
    real(c_double) :: particle_spacing
    integer(c_int) :: full_count
    real(c_double) :: full_fraction
    real(c_double) :: particle_radius
    real(c_double) :: cell_size
    integer(c_int) :: validate
    integer(c_int) :: include_ghosts
    integer(c_int) :: has_mpi_comm  ! 1: inside an MPI job on mpi_comm
    integer(c_int) :: mpi_comm      ! the communicator (a Fortran MPI handle is an integer)
  end type

  ! The C struct's uint64_t counters read as 64-bit integers.
  type, bind(C) :: voxspan_step_stats
    integer(c_int64_t) :: step
    real(c_double) :: time
    integer(c_int) :: rendered, status
    integer(c_int64_t) :: particles, owned, boundary, dropped_nonfinite, not_in_grid
    integer(c_int64_t) :: cells, cells_empty, cells_partial, cells_full, cells_inner_empty, &
                          cells_inner_full
    integer(c_int) :: full_count, grid_built
    real(c_double) :: cell_size
    real(c_double) :: seconds_classify, seconds_compact, seconds_pipeline, seconds_total
  end type

  interface
    subroutine voxspan_set_log_level(level) bind(C)
      import :: c_int
      integer(c_int), value :: level
    end subroutine

    function voxspan_last_error_c() bind(C, name="voxspan_last_error") result(message)
      import :: c_ptr
      type(c_ptr) :: message
    end function

    function voxspan_version_c() bind(C, name="voxspan_version") result(version)
      import :: c_ptr
      type(c_ptr) :: version
    end function

    subroutine voxspan_adapter_options_init(options) bind(C)
      import :: voxspan_adapter_options
      type(voxspan_adapter_options), intent(out) :: options
    end subroutine

    function voxspan_adapter_create(options) bind(C) result(adapter)
      import :: voxspan_adapter_options, c_ptr
      type(voxspan_adapter_options), intent(in) :: options
      type(c_ptr) :: adapter
    end function

    ! The in-situ runtime, configured by a YAML file; config_path is a NUL-terminated string:
    ! voxspan_adapter_create_from_config(opt, "insitu.yaml" // c_null_char).
    function voxspan_adapter_create_from_config(options, config_path) bind(C) result(adapter)
      import :: voxspan_adapter_options, c_ptr, c_char
      type(voxspan_adapter_options), intent(in) :: options
      character(kind=c_char), dimension(*), intent(in) :: config_path
      type(c_ptr) :: adapter
    end function

    function voxspan_adapter_execute_last(adapter, step, time, particles, grid) bind(C) result(rc)
      import :: c_ptr, c_int64_t, c_double, c_int
      type(c_ptr), value :: adapter, particles, grid
      integer(c_int64_t), value :: step
      real(c_double), value :: time
      integer(c_int) :: rc
    end function

    function voxspan_adapter_finish(adapter) bind(C) result(rc)
      import :: c_ptr, c_int
      type(c_ptr), value :: adapter
      integer(c_int) :: rc
    end function

    subroutine voxspan_adapter_destroy(adapter) bind(C)
      import :: c_ptr
      type(c_ptr), value :: adapter
    end subroutine

    function voxspan_adapter_execute(adapter, step, time, particles, grid) bind(C) result(rc)
      import :: c_ptr, c_int64_t, c_double, c_int
      type(c_ptr), value :: adapter, particles, grid
      integer(c_int64_t), value :: step
      real(c_double), value :: time
      integer(c_int) :: rc
    end function

    ! The solver's walls and obstacles (copied); kept may be c_null_ptr.
    function voxspan_adapter_set_scenery(adapter, scenery, kept) bind(C) result(rc)
      import :: c_ptr, c_int
      type(c_ptr), value :: adapter, scenery, kept
      integer(c_int) :: rc
    end function

    ! Compacts the named particle attribute beside the surface-shell particles.
    function voxspan_adapter_add_attribute(adapter, name) bind(C) result(rc)
      import :: c_ptr, c_int, c_char
      type(c_ptr), value :: adapter
      character(kind=c_char), dimension(*), intent(in) :: name
      integer(c_int) :: rc
    end function

    ! 1 when the runtime renders at (step, time): pass the attributes the config names then.
    function voxspan_adapter_is_render_step(adapter, step, time) bind(C) result(yes)
      import :: c_ptr, c_int, c_int64_t, c_double
      type(c_ptr), value :: adapter
      integer(c_int64_t), value :: step
      real(c_double), value :: time
      integer(c_int) :: yes
    end function

    ! The summary line into buffer (NUL-terminated, cut to size); its full length.
    function voxspan_adapter_summary(adapter, buffer, size) bind(C) result(length)
      import :: c_ptr, c_char, c_size_t
      type(c_ptr), value :: adapter
      character(kind=c_char), dimension(*), intent(out) :: buffer
      integer(c_size_t), value :: size
      integer(c_size_t) :: length
    end function

    ! The latest render step's surface-shell particles (packed x, y, z, radius floats in
    ! xyzr: c_f_pointer it to real(c_float) :: a(4, count)); their count. x, y, z are
    ! measured from voxspan_adapter_boundary_origin's point.
    function voxspan_adapter_boundary(adapter, xyzr) bind(C) result(count)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: adapter
      type(c_ptr), intent(out) :: xyzr
      integer(c_size_t) :: count
    end function

    ! The world coordinates the surface-shell particles are measured from (a particle is at
    ! origin + (x, y, z)): the world's origin for ordinary scenes.
    subroutine voxspan_adapter_boundary_origin(adapter, origin) bind(C)
      import :: c_ptr, c_double
      type(c_ptr), value :: adapter
      real(c_double), intent(out) :: origin(3)
    end subroutine

    ! The scenery kept from the last set_scenery, as voxspan_adapter_boundary gives particles.
    function voxspan_adapter_scenery(adapter, xyzr) bind(C) result(count)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: adapter
      type(c_ptr), intent(out) :: xyzr
      integer(c_size_t) :: count
    end function

    ! The latest render step's cell states (bytes, x fastest) in states; the number of cells.
    function voxspan_adapter_cell_states(adapter, origin, cell_size, dims, states) bind(C) &
        result(count)
      import :: c_ptr, c_size_t, c_double, c_int
      type(c_ptr), value :: adapter
      real(c_double), intent(out) :: origin(3), cell_size
      integer(c_int), intent(out) :: dims(3)
      type(c_ptr), intent(out) :: states
      integer(c_size_t) :: count
    end function

    ! A compacted attribute of the latest render step: its floats in values, `components` a
    ! particle; the float count (0 when the name was not asked for).
    function voxspan_adapter_attribute(adapter, name, values, components) bind(C) result(count)
      import :: c_ptr, c_size_t, c_char, c_int
      type(c_ptr), value :: adapter
      character(kind=c_char), dimension(*), intent(in) :: name
      type(c_ptr), intent(out) :: values
      integer(c_int), intent(out) :: components
      integer(c_size_t) :: count
    end function

    function voxspan_adapter_stats(adapter, stats) bind(C) result(rc)
      import :: c_ptr, c_int, voxspan_step_stats
      type(c_ptr), value :: adapter
      type(voxspan_step_stats), intent(out) :: stats
      integer(c_int) :: rc
    end function

    function voxspan_particles_create() bind(C) result(particles)
      import :: c_ptr
      type(c_ptr) :: particles
    end function

    subroutine voxspan_particles_destroy(particles) bind(C)
      import :: c_ptr
      type(c_ptr), value :: particles
    end subroutine

    function voxspan_particles_set_aos(particles, type, xyz, count, stride_bytes) bind(C) &
        result(rc)
      import :: c_ptr, c_int, c_size_t
      type(c_ptr), value :: particles, xyz
      integer(c_int), value :: type
      integer(c_size_t), value :: count, stride_bytes
      integer(c_int) :: rc
    end function

    function voxspan_particles_set_soa(particles, type, x, y, z, count) bind(C) result(rc)
      import :: c_ptr, c_int, c_size_t
      type(c_ptr), value :: particles, x, y, z
      integer(c_int), value :: type
      integer(c_size_t), value :: count
      integer(c_int) :: rc
    end function

    function voxspan_particles_set_owned(particles, owned) bind(C) result(rc)
      import :: c_ptr, c_int, c_size_t
      type(c_ptr), value :: particles
      integer(c_size_t), value :: owned
      integer(c_int) :: rc
    end function

    function voxspan_particles_set_radius(particles, radius) bind(C) result(rc)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: particles
      real(c_double), value :: radius
      integer(c_int) :: rc
    end function

    ! Per-particle radii (stride 0: packed); c_null_ptr clears them.
    function voxspan_particles_set_radii(particles, type, radii, stride_bytes) bind(C) &
        result(rc)
      import :: c_ptr, c_int, c_size_t
      type(c_ptr), value :: particles, radii
      integer(c_int), value :: type
      integer(c_size_t), value :: stride_bytes
      integer(c_int) :: rc
    end function

    ! A named attribute, one value a particle (stride 0: packed); the name is copied.
    function voxspan_particles_set_scalar(particles, name, type, values, stride_bytes) &
        bind(C) result(rc)
      import :: c_ptr, c_int, c_size_t, c_char
      type(c_ptr), value :: particles, values
      character(kind=c_char), dimension(*), intent(in) :: name
      integer(c_int), value :: type
      integer(c_size_t), value :: stride_bytes
      integer(c_int) :: rc
    end function

    ! A named attribute, x, y, z a particle (a real :: v(3, n) array; stride 0: packed).
    function voxspan_particles_set_vector(particles, name, type, xyz, stride_bytes) &
        bind(C) result(rc)
      import :: c_ptr, c_int, c_size_t, c_char
      type(c_ptr), value :: particles, xyz
      character(kind=c_char), dimension(*), intent(in) :: name
      integer(c_int), value :: type
      integer(c_size_t), value :: stride_bytes
      integer(c_int) :: rc
    end function

    subroutine voxspan_particles_clear_attributes(particles) bind(C)
      import :: c_ptr
      type(c_ptr), value :: particles
    end subroutine

    function voxspan_grid_create() bind(C) result(grid)
      import :: c_ptr
      type(c_ptr) :: grid
    end function

    subroutine voxspan_grid_destroy(grid) bind(C)
      import :: c_ptr
      type(c_ptr), value :: grid
    end subroutine

    function voxspan_grid_set_offsets(grid, origin, cell_size, dims, index_type, offsets) &
        bind(C) result(rc)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: grid, offsets
      real(c_double), intent(in) :: origin(3)
      real(c_double), value :: cell_size
      integer(c_int), intent(in) :: dims(3)
      integer(c_int), value :: index_type
      integer(c_int) :: rc
    end function

    ! Cell c holds sorted slots [cell_begin(c), cell_end(c)).
    function voxspan_grid_set_begin_end(grid, origin, cell_size, dims, index_type, cell_begin, &
                                        cell_end) bind(C) result(rc)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: grid, cell_begin, cell_end
      real(c_double), intent(in) :: origin(3)
      real(c_double), value :: cell_size
      integer(c_int), intent(in) :: dims(3)
      integer(c_int), value :: index_type
      integer(c_int) :: rc
    end function

    function voxspan_grid_set_cell_index(grid, origin, cell_size, dims, index_type, cell_of) &
        bind(C) result(rc)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: grid, cell_of
      real(c_double), intent(in) :: origin(3)
      real(c_double), value :: cell_size
      integer(c_int), intent(in) :: dims(3)
      integer(c_int), value :: index_type
      integer(c_int) :: rc
    end function

    function voxspan_grid_set_geometry(grid, origin, cell_size, dims) bind(C) result(rc)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value :: grid
      real(c_double), intent(in) :: origin(3)
      real(c_double), value :: cell_size
      integer(c_int), intent(in) :: dims(3)
      integer(c_int) :: rc
    end function

    function voxspan_grid_set_order(grid, index_type, order) bind(C) result(rc)
      import :: c_ptr, c_int
      type(c_ptr), value :: grid, order
      integer(c_int), value :: index_type
      integer(c_int) :: rc
    end function

    function voxspan_grid_set_index_base(grid, base) bind(C) result(rc)
      import :: c_ptr, c_int
      type(c_ptr), value :: grid
      integer(c_int), value :: base
      integer(c_int) :: rc
    end function

    subroutine voxspan_grid_clear(grid) bind(C)
      import :: c_ptr
      type(c_ptr), value :: grid
    end subroutine
  end interface

contains

  ! The message of the latest failed call on this thread, as a Fortran string.
  function voxspan_error_message() result(message)
    character(len=:), allocatable :: message
    message = fortran_string(voxspan_last_error_c())
  end function

  ! The loaded library's version ("0.1.0").
  function voxspan_version() result(version)
    character(len=:), allocatable :: version
    version = fortran_string(voxspan_version_c())
  end function

  ! A NUL-terminated C string as a Fortran string.
  function fortran_string(p) result(text)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: text
    character(kind=c_char), pointer :: chars(:)
    integer :: n
    interface
      function strlen(s) bind(C, name="strlen") result(length)
        import :: c_ptr, c_size_t
        type(c_ptr), value :: s
        integer(c_size_t) :: length
      end function
    end interface
    n = int(strlen(p))
    call c_f_pointer(p, chars, [n])
    allocate(character(len=n) :: text)
    text = transfer(chars(1:n), text)
  end function

end module voxspan
