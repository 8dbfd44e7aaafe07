! A Fortran solver compiles the installed module (Voxspan_FORTRAN_MODULE) with its sources.
program consumer_f
  use voxspan
  implicit none
  call voxspan_set_log_level(1)
  print '(a)', voxspan_version()
  if (len_trim(voxspan_version()) == 0) error stop 1
end program consumer_f
