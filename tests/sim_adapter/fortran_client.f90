! A Fortran solver's use of the C API through the voxspan module: a 4 x 4 x 4 lattice in
! double SoA arrays with a 1-based per-particle cell index, then a bad grid, then walls; then
! per-particle data (a pressure, a velocity, radii) compacted and read back, the grid as begin
! and end arrays, the render-step question and the version.
program fortran_client
  use voxspan
  implicit none
  integer, parameter :: n = 64
  real(c_double), target :: x(n), y(n), z(n), pressure(n), velocity(3, n)
  real(c_float), target :: radii(n)
  integer(c_int32_t), target :: cell(n), cell_begin(8), cell_end(8), order(n)
  real(c_float), pointer :: values(:)
  type(c_ptr) :: found
  integer(c_int) :: components
  type(voxspan_adapter_options) :: opt
  type(voxspan_step_stats) :: stats
  type(c_ptr) :: adapter, particles, grid, walls
  integer(c_size_t), target :: kept = 0
  real(c_double) :: origin(3) = 0
  integer(c_int) :: dims(3) = 2, rc
  integer :: i, j, k, p

  p = 0
  do k = 0, 3
    do j = 0, 3
      do i = 0, 3
        p = p + 1
        x(p) = i + 0.5d0
        y(p) = j + 0.5d0
        z(p) = k + 0.5d0
        cell(p) = 1 + i / 2 + 2 * (j / 2) + 4 * (k / 2)
      end do
    end do
  end do

  call voxspan_set_log_level(0)
  call voxspan_adapter_options_init(opt)
  opt%particle_spacing = 1
  opt%validate = 1
  adapter = voxspan_adapter_create(opt)
  particles = voxspan_particles_create()
  grid = voxspan_grid_create()
  if (.not. c_associated(adapter)) error stop "adapter not created"

  rc = voxspan_particles_set_soa(particles, VOXSPAN_FLOAT64, c_loc(x), c_loc(y), c_loc(z), &
                                 int(n, c_size_t))
  rc = voxspan_grid_set_cell_index(grid, origin, 2d0, dims, VOXSPAN_INT32, c_loc(cell))
  rc = voxspan_grid_set_index_base(grid, 1)
  rc = voxspan_adapter_execute(adapter, 0_c_int64_t, 0d0, particles, grid)
  if (rc /= VOXSPAN_OK) error stop "execute failed"
  rc = voxspan_adapter_stats(adapter, stats)
  if (stats%boundary /= 64 .or. stats%cells_full /= 8 .or. stats%grid_built /= 1) then
    print *, "boundary", stats%boundary, "full", stats%cells_full
    error stop "wrong classification"
  end if

  ! A cell index that lies (particle 1 claimed by cell 8): caught by validation, named.
  cell(1) = 8
  rc = voxspan_adapter_execute(adapter, 1_c_int64_t, 0d0, particles, grid)
  if (rc /= VOXSPAN_INVALID_INPUT) error stop "bad grid not caught"
  if (index(voxspan_error_message(), "particle 0 at") == 0) then
    print *, voxspan_error_message()
    error stop "message does not name the particle"
  end if

  ! Walls (the lattice's first row) given as scenery: copied, every one kept.
  walls = voxspan_particles_create()
  rc = voxspan_particles_set_soa(walls, VOXSPAN_FLOAT64, c_loc(x), c_loc(y), c_loc(z), 4_c_size_t)
  rc = voxspan_adapter_set_scenery(adapter, walls, c_loc(kept))
  if (rc /= VOXSPAN_OK .or. kept /= 4) error stop "scenery not kept"
  call voxspan_particles_destroy(walls)

  ! Per-particle data: a pressure and a velocity compacted beside the shell, radii.
  pressure = [(1000d0 + i, i = 1, n)]
  velocity = 0
  velocity(3, :) = -2
  radii = 0.5
  rc = voxspan_adapter_add_attribute(adapter, "pressure" // c_null_char)
  if (rc /= VOXSPAN_OK) error stop "add_attribute failed"
  rc = voxspan_adapter_add_attribute(adapter, "velocity" // c_null_char)
  rc = voxspan_particles_set_scalar(particles, "pressure" // c_null_char, VOXSPAN_FLOAT64, &
                                    c_loc(pressure), 0_c_size_t)
  if (rc /= VOXSPAN_OK) error stop "set_scalar failed"
  rc = voxspan_particles_set_vector(particles, "velocity" // c_null_char, VOXSPAN_FLOAT64, &
                                    c_loc(velocity), 0_c_size_t)
  if (rc /= VOXSPAN_OK) error stop "set_vector failed"
  rc = voxspan_particles_set_radii(particles, VOXSPAN_FLOAT32, c_loc(radii), 0_c_size_t)
  if (rc /= VOXSPAN_OK) error stop "set_radii failed"
  ! The same cells as begin and end arrays over particles stored in cell order (order: 1-based).
  cell(1) = 1
  p = 0
  do k = 1, 8
    cell_begin(k) = p + 1
    do i = 1, n
      if (cell(i) == k) then
        p = p + 1
        order(p) = i
      end if
    end do
    cell_end(k) = p + 1
  end do
  rc = voxspan_grid_set_begin_end(grid, origin, 2d0, dims, VOXSPAN_INT32, c_loc(cell_begin), &
                                  c_loc(cell_end))
  rc = voxspan_grid_set_order(grid, VOXSPAN_INT32, c_loc(order))
  if (voxspan_adapter_is_render_step(adapter, 2_c_int64_t, 0d0) /= 1) error stop "not a render step"
  rc = voxspan_adapter_execute(adapter, 2_c_int64_t, 0d0, particles, grid)
  if (rc /= VOXSPAN_OK) then
    print *, voxspan_error_message()
    error stop "execute with attributes failed"
  end if
  if (voxspan_adapter_attribute(adapter, "pressure" // c_null_char, found, components) /= 64 &
      .or. components /= 1) error stop "pressure not compacted"
  call c_f_pointer(found, values, [64])
  if (minval(values) < 1001 .or. maxval(values) > 1064) error stop "pressure values wrong"
  if (voxspan_adapter_attribute(adapter, "velocity" // c_null_char, found, components) /= 192 &
      .or. components /= 3) error stop "velocity not compacted"
  call c_f_pointer(found, values, [192])
  if (values(3) /= -2) error stop "velocity's z wrong"
  if (voxspan_adapter_boundary(adapter, found) /= 64) error stop "boundary count"
  call c_f_pointer(found, values, [4 * 64])
  if (values(4) /= 0.5) error stop "radii not used"
  call voxspan_particles_clear_attributes(particles)
  call voxspan_grid_clear(grid)
  if (len(voxspan_version()) == 0) error stop "no version"

  call voxspan_grid_destroy(grid)
  call voxspan_particles_destroy(particles)
  call voxspan_adapter_destroy(adapter)
  print *, "fortran client OK"
end program
