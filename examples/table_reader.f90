! Evaluate a railcontact table (a .nc file in tables/) from Fortran with netCDF-Fortran.
!
! The same reader as examples/table_reader.c, from the same documented attributes:
!   global table_axes, spline_degree (= 3), railcontact_table_format (= 1, 2 or 3: 2 stores
!   the node values on a block, 3 none; this reader reads only the coefficients);
!   axis A: attribute spline_knots (name of its knot vector, length = nodes + 4);
!   variable V: attribute bspline_coefficients (name of its coefficient array).
! The coefficients are read as one flat buffer in the file's (C) order, the last axis varying
! fastest, so the index arithmetic is the C program's.
!
! Build:  gfortran -O2 -o table_reader_f examples/table_reader.f90 $(nf-config --fflags) \
!             $(nf-config --flibs)
! Run:    ./table_reader_f tables/creep_modified_strip.nc force_ratio < points.txt
!         (one point per line: D table coordinates; prints value and D first derivatives)
program table_reader
  use netcdf
  implicit none
  include 'netcdf.inc'
  integer, parameter :: dp = kind(1.0d0), maxd = 8
  character(len=4096) :: path, varname, axes_text, name
  integer :: ncid, varid, d, e, j, k, ndim, ios, pos, version, degree, terms
  integer :: ncoef(maxd), span(maxd), n
  integer(8) :: stride(maxd), offset
  type :: knot_vector
    real(dp), allocatable :: t(:)
  end type
  type(knot_vector) :: knots(maxd)
  real(dp), allocatable :: coef(:)
  real, allocatable :: coef_single(:)
  integer :: xtype
  real(dp) :: x(maxd), nb(0:3, maxd), db(0:3, maxd), value, grad(maxd), prod, partial(maxd)

  if (command_argument_count() /= 2) then
    write (0, '(a)') 'usage: table_reader_f TABLE.nc VARIABLE < points'
    stop 2
  end if
  call get_command_argument(1, path)
  call get_command_argument(2, varname)
  call check(nf90_open(trim(path), nf90_nowrite, ncid))
  call check(nf90_get_att(ncid, nf90_global, 'railcontact_table_format', version))
  call check(nf90_get_att(ncid, nf90_global, 'spline_degree', degree))
  if (version < 1 .or. version > 3 .or. degree /= 3) then
    write (0, '(a)') 'unsupported table format or spline degree'
    stop 1
  end if

  ! axes and knot vectors
  axes_text = ''
  call check(nf90_get_att(ncid, nf90_global, 'table_axes', axes_text))
  ndim = 0
  do
    axes_text = adjustl(axes_text)
    if (len_trim(axes_text) == 0) exit
    pos = index_of_blank(axes_text)
    name = axes_text(1:pos - 1)
    axes_text = axes_text(pos:)
    ndim = ndim + 1
    call check(nf90_inq_varid(ncid, trim(name), varid))
    name = ''
    call check(nf90_get_att(ncid, varid, 'spline_knots', name))
    call check(nf90_inq_varid(ncid, trim(name), varid))
    n = variable_size(ncid, varid)
    allocate (knots(ndim)%t(0:n - 1))
    call check(nf_get_var_double(ncid, varid, knots(ndim)%t))
    ncoef(ndim) = n - 4
  end do

  ! coefficients, flat, C order
  call check(nf90_inq_varid(ncid, trim(varname), varid))
  name = ''
  call check(nf90_get_att(ncid, varid, 'bspline_coefficients', name))
  call check(nf90_inq_varid(ncid, trim(name), varid))
  allocate (coef(0:variable_size(ncid, varid) - 1))
  ! a float variable is read as float and widened here (libnetcdf 4.9.0 re-applies a
  ! variable's quantisation when it converts float to double on reading; see table_reader.c)
  call check(nf90_inquire_variable(ncid, varid, xtype=xtype))
  if (xtype == nf90_float) then
    allocate (coef_single(0:size(coef) - 1))
    call check(nf_get_var_real(ncid, varid, coef_single))
    coef = real(coef_single, dp)
    deallocate (coef_single)
  else
    call check(nf_get_var_double(ncid, varid, coef))
  end if
  call check(nf90_close(ncid))
  stride(ndim) = 1
  do d = ndim - 1, 1, -1
    stride(d) = stride(d + 1) * ncoef(d + 1)
  end do
  if (stride(1) * ncoef(1) /= size(coef, kind=8)) then
    write (0, '(a)') 'coefficient array does not match the knot vectors'
    stop 1
  end if

  terms = 4**ndim
  do
    read (*, *, iostat=ios) x(1:ndim)
    if (ios /= 0) exit
    do d = 1, ndim
      span(d) = find_span(knots(d)%t, ncoef(d), x(d))
      call cubic_basis(knots(d)%t, span(d), x(d), nb(:, d), db(:, d))
    end do
    value = 0.0_dp
    grad = 0.0_dp
    do k = 0, terms - 1
      offset = 0
      prod = 1.0_dp
      partial = 1.0_dp
      do d = 1, ndim
        j = iand(shiftr(k, 2 * (d - 1)), 3)
        offset = offset + int(span(d) - 3 + j, 8) * stride(d)
        prod = prod * nb(j, d)
        do e = 1, ndim
          if (e == d) then
            partial(e) = partial(e) * db(j, d)
          else
            partial(e) = partial(e) * nb(j, d)
          end if
        end do
      end do
      value = value + coef(offset) * prod
      grad(1:ndim) = grad(1:ndim) + coef(offset) * partial(1:ndim)
    end do
    write (*, '(*(1x, es25.17e3))') value, grad(1:ndim)
  end do

contains

  subroutine check(code)
    integer, intent(in) :: code
    if (code /= nf90_noerr) then
      write (0, '(a)') 'netCDF error: '//trim(nf90_strerror(code))
      stop 1
    end if
  end subroutine

  integer function index_of_blank(text)
    character(len=*), intent(in) :: text
    index_of_blank = index(text, ' ')
  end function

  integer function variable_size(ncid, varid)
    integer, intent(in) :: ncid, varid
    integer :: ndims, dimids(nf90_max_var_dims), len, i
    call check(nf90_inquire_variable(ncid, varid, ndims=ndims, dimids=dimids))
    variable_size = 1
    do i = 1, ndims
      call check(nf90_inquire_dimension(ncid, dimids(i), len=len))
      variable_size = variable_size * len
    end do
  end function

  ! Knot span s (0-based) with t(s) <= x < t(s+1), 3 <= s <= ncoef - 1 (x clamped).
  integer function find_span(t, ncoef, x)
    real(dp), intent(in) :: t(0:), x
    integer, intent(in) :: ncoef
    integer :: lo, hi, mid
    lo = 3
    hi = ncoef
    if (x >= t(hi)) then
      find_span = hi - 1
      return
    end if
    if (x <= t(lo)) then
      find_span = lo
      return
    end if
    do while (hi - lo > 1)
      mid = (lo + hi) / 2
      if (t(mid) <= x) then
        lo = mid
      else
        hi = mid
      end if
    end do
    find_span = lo
  end function

  ! The 4 non-zero cubic B-splines at x in span s and their first derivatives (Cox-de Boor,
  ! triangular form of Piegl & Tiller, The NURBS Book, A2.3).
  subroutine cubic_basis(t, s, x, nb, db)
    real(dp), intent(in) :: t(0:), x
    integer, intent(in) :: s
    real(dp), intent(out) :: nb(0:3), db(0:3)
    real(dp) :: left(3), right(3), ndu(0:3, 0:3), saved, temp, dd
    integer :: jj, r
    ndu(0, 0) = 1.0_dp
    do jj = 1, 3
      left(jj) = x - t(s + 1 - jj)
      right(jj) = t(s + jj) - x
      saved = 0.0_dp
      do r = 0, jj - 1
        ndu(jj, r) = right(r + 1) + left(jj - r)
        temp = ndu(r, jj - 1) / ndu(jj, r)
        ndu(r, jj) = saved + right(r + 1) * temp
        saved = left(jj - r) * temp
      end do
      ndu(jj, jj) = saved
    end do
    do r = 0, 3
      nb(r) = ndu(r, 3)
      dd = 0.0_dp
      if (r >= 1) dd = dd + ndu(r - 1, 2) / ndu(3, r - 1)
      if (r <= 2) dd = dd - ndu(r, 2) / ndu(3, r)
      db(r) = 3.0_dp * dd
    end do
  end subroutine

end program
