/* Evaluate a railcontact table (a .nc file in tables/) from C with the netCDF C library.
 *
 * Everything is found through the attributes the file documents (see docs/tables.md):
 *   global  table_axes          axis names, in order, separated by blanks
 *   global  table_variables     variable names
 *   global  spline_degree       3 (cubic)
 *   global  railcontact_table_format  1, 2 or 3 (refuse other versions; 2 stores the node
 *                                     values on a block, 3 none: this reader reads only the
 *                                     coefficients)
 *   axis A  A:spline_knots      name of its knot vector (A_knots, length = nodes + 4)
 *   var V   V:bspline_coefficients  name of its coefficient array (C order, axes as listed)
 *
 *   V(x1..xD) = sum c[i1..iD] B(i1; x1) ... B(iD; xD), B = cubic B-splines of the knot vectors.
 *
 * Build:  gcc -O2 -o table_reader examples/table_reader.c $(nc-config --cflags) \
 *             $(nc-config --libs) -lm
 * Run:    ./table_reader tables/creep_modified_strip.nc force_ratio < points.txt
 *         (one point per line: D table coordinates; prints the value and the D first
 *          partial derivatives, in axis order)
 * Points outside the grid are evaluated with the end polynomial pieces (no range check here:
 * the axes' out_of_range attribute says what a careful reader should do).
 *
 * creep_exact's coordinates from physical inputs (exact_table_coordinates below):
 *         ./table_reader --exact-coordinates < contacts.txt
 *         (one contact per line: xi_x xi_y phi a0 b0 nu N E mu, SI units; prints
 *          ln(a0/b0) nu s theta tau, the table's five coordinates), so that
 *         ./table_reader --exact-coordinates < contacts.txt \
 *             | ./table_reader tables/creep_exact.nc force_ratio_parallel
 *         gives f_par at each contact (docs/tables.md: the forces from f_par, f_perp, theta).
 */
#include <math.h>
#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXD 8
#define CHECK(call) do { int _s = (call); if (_s != NC_NOERR) { \
    fprintf(stderr, "netCDF error at %s:%d: %s\n", __FILE__, __LINE__, nc_strerror(_s)); \
    exit(1); } } while (0)

/* A text attribute as a new NUL-terminated string. */
static char *text_attribute(int ncid, int varid, const char *name)
{
    size_t len;
    CHECK(nc_inq_attlen(ncid, varid, name, &len));
    char *s = malloc(len + 1);
    CHECK(nc_get_att_text(ncid, varid, name, s));
    s[len] = '\0';
    return s;
}

static int int_attribute(int ncid, int varid, const char *name)
{
    int v;
    CHECK(nc_get_att_int(ncid, varid, name, &v));
    return v;
}

/* A whole variable (any rank) as doubles; *n receives its number of elements. A float
 * variable is read as float and widened here: libnetcdf 4.9.0 (Debian 12) re-applies a
 * variable's quantisation (_QuantizeGranularBitRoundNumberOfSignificantDigits) when it
 * converts float to double on reading, which moved 70 of creep_exact's 3-digit stick-area
 * coefficients by up to 7.6e-6 (measured: nc_get_var_double against nc_get_var_float). */
static double *read_doubles(int ncid, const char *name, size_t *n)
{
    int varid, ndims, dimids[NC_MAX_VAR_DIMS];
    CHECK(nc_inq_varid(ncid, name, &varid));
    CHECK(nc_inq_varndims(ncid, varid, &ndims));
    CHECK(nc_inq_vardimid(ncid, varid, dimids));
    *n = 1;
    for (int d = 0; d < ndims; d++) {
        size_t len;
        CHECK(nc_inq_dimlen(ncid, dimids[d], &len));
        *n *= len;
    }
    double *data = malloc(*n * sizeof(double));
    nc_type type;
    CHECK(nc_inq_vartype(ncid, varid, &type));
    if (type == NC_FLOAT) {
        float *single = malloc(*n * sizeof(float));
        CHECK(nc_get_var_float(ncid, varid, single));
        for (size_t i = 0; i < *n; i++) data[i] = (double)single[i];
        free(single);
    } else {
        CHECK(nc_get_var_double(ncid, varid, data));
    }
    return data;
}

/* Knot span s with t[s] <= x < t[s+1], 3 <= s <= ncoef - 1 (x clamped to the spline's range). */
static int find_span(const double *t, int ncoef, double x)
{
    int lo = 3, hi = ncoef;
    if (x >= t[hi]) return hi - 1;
    if (x <= t[lo]) return lo;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (t[mid] <= x) lo = mid; else hi = mid;
    }
    return lo;
}

/* The 4 non-zero cubic B-splines B(s-3+j; x), j = 0..3, and their first derivatives
 * (Cox-de Boor recursion in the triangular form of Piegl & Tiller, The NURBS Book, A2.3). */
static void cubic_basis(const double *t, int s, double x, double N[4], double dN[4])
{
    double left[4], right[4], ndu[4][4];
    ndu[0][0] = 1.0;
    for (int j = 1; j <= 3; j++) {
        left[j] = x - t[s + 1 - j];
        right[j] = t[s + j] - x;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            ndu[j][r] = right[r + 1] + left[j - r];      /* knot difference, > 0 */
            double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for (int r = 0; r <= 3; r++) {
        N[r] = ndu[r][3];
        double d = 0.0;                                  /* B'(i,3) from the degree-2 values */
        if (r >= 1) d += ndu[r - 1][2] / ndu[3][r - 1];
        if (r <= 2) d -= ndu[r][2] / ndu[3][r];
        dN[r] = 3.0 * d;
    }
}

/* ---- creep_exact: table coordinates from physical inputs ------------------------------ */

/* Kalker's creep coefficients (Kalker 1967; Kalker 1990, Table E.3), as in
 * fmu_src/railcontact/data/kalker_coefficients.csv: a0/b0 = 0.1 ... 1 and 1/(b0/a0) for
 * b0/a0 = 0.9 ... 0.1; [coefficient C11, C22, C23][nu = 0, 0.25, 0.5][a0/b0]. */
#define KALKER_N 19
static const double KALKER_A0_OVER_B0[KALKER_N] = {
    0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.0 / 0.9, 1.0 / 0.8, 1.0 / 0.7,
    1.0 / 0.6, 1.0 / 0.5, 1.0 / 0.4, 1.0 / 0.3, 1.0 / 0.2, 1.0 / 0.1};
static const double KALKER_NU[3] = {0.0, 0.25, 0.5};
static const double KALKER_C[3][3][KALKER_N] = {
    { /* C11 */
        {2.51, 2.59, 2.68, 2.78, 2.88, 2.98, 3.09, 3.19, 3.29, 3.40, 3.51, 3.65, 3.82, 4.06, 4.37,
         4.84, 5.57, 6.96, 10.7},
        {3.31, 3.37, 3.44, 3.53, 3.62, 3.72, 3.81, 3.91, 4.01, 4.12, 4.22, 4.36, 4.54, 4.78, 5.10,
         5.57, 6.34, 7.78, 11.7},
        {4.85, 4.81, 4.80, 4.82, 4.83, 4.91, 4.97, 5.05, 5.12, 5.20, 5.30, 5.42, 5.58, 5.80, 6.11,
         6.57, 7.34, 8.82, 12.9}},
    { /* C22 */
        {2.51, 2.59, 2.68, 2.78, 2.88, 2.98, 3.09, 3.19, 3.29, 3.40, 3.51, 3.65, 3.82, 4.06, 4.37,
         4.84, 5.57, 6.96, 10.7},
        {2.52, 2.63, 2.75, 2.88, 3.01, 3.14, 3.28, 3.41, 3.54, 3.67, 3.81, 3.99, 4.21, 4.50, 4.90,
         5.48, 6.40, 8.14, 12.8},
        {2.53, 2.66, 2.81, 2.98, 3.14, 3.31, 3.48, 3.65, 3.82, 3.98, 4.16, 4.39, 4.67, 5.04, 5.56,
         6.31, 7.51, 9.79, 16.0}},
    { /* C23 */
        {.334, .483, .607, .720, .827, .930, 1.03, 1.13, 1.23, 1.33, 1.44, 1.58, 1.76, 2.01, 2.35,
         2.88, 3.79, 5.72, 12.2},
        {.473, .603, .715, .823, .929, 1.03, 1.14, 1.25, 1.36, 1.47, 1.59, 1.75, 1.95, 2.23, 2.62,
         3.24, 4.32, 6.63, 14.6},
        {.731, .809, .889, .977, 1.07, 1.18, 1.29, 1.40, 1.51, 1.63, 1.77, 1.94, 2.18, 2.50, 2.96,
         3.70, 5.01, 7.89, 18.0}}};

/* Second derivatives M of the not-a-knot cubic spline through (x[i], y[i]), i < n <= KALKER_N
 * (the interpolant of scipy's CubicSpline(bc_type="not-a-knot")): the usual continuity rows,
 * and a continuous third derivative at x[1] and x[n-2]; solved by Gaussian elimination with
 * partial pivoting (n is small). */
static void not_a_knot_spline(int n, const double *x, const double *y, double *M)
{
    double A[KALKER_N][KALKER_N + 1] = {{0.0}};
    double h[KALKER_N];
    for (int i = 0; i < n - 1; i++) h[i] = x[i + 1] - x[i];
    A[0][0] = h[1]; A[0][1] = -(h[0] + h[1]); A[0][2] = h[0];
    A[n - 1][n - 3] = h[n - 2]; A[n - 1][n - 2] = -(h[n - 3] + h[n - 2]);
    A[n - 1][n - 1] = h[n - 3];
    for (int i = 1; i < n - 1; i++) {
        A[i][i - 1] = h[i - 1];
        A[i][i] = 2.0 * (h[i - 1] + h[i]);
        A[i][i + 1] = h[i];
        A[i][n] = 6.0 * ((y[i + 1] - y[i]) / h[i] - (y[i] - y[i - 1]) / h[i - 1]);
    }
    for (int c = 0; c < n; c++) {
        int p = c;
        for (int r = c + 1; r < n; r++) if (fabs(A[r][c]) > fabs(A[p][c])) p = r;
        for (int k = 0; k <= n; k++) { double t = A[c][k]; A[c][k] = A[p][k]; A[p][k] = t; }
        for (int r = c + 1; r < n; r++) {
            double f = A[r][c] / A[c][c];
            for (int k = c; k <= n; k++) A[r][k] -= f * A[c][k];
        }
    }
    for (int r = n - 1; r >= 0; r--) {
        double sum = A[r][n];
        for (int k = r + 1; k < n; k++) sum -= A[r][k] * M[k];
        M[r] = sum / A[r][r];
    }
}

static double spline_value(int n, const double *x, const double *y, const double *M, double t)
{
    int i = 0;
    while (i < n - 2 && t > x[i + 1]) i++;
    double h = x[i + 1] - x[i], a = (x[i + 1] - t) / h, b = (t - x[i]) / h;
    return a * y[i] + b * y[i + 1] + ((a * a * a - a) * M[i] + (b * b * b - b) * M[i + 1])
           * h * h / 6.0;
}

/* Kalker's C11, C22, C23 at a0/b0 in [0.1, 10] and nu in [0, 0.5], the interpolant of
 * railcontact.kalker_coefficients inside the table: per tabulated nu a not-a-knot cubic
 * spline of ln C in ln(a0/b0), then 1/C quadratic in nu (Lagrange). Returns 0, or -1 outside
 * those ranges (the creep_exact table covers no more). */
static int kalker_coefficients(double a0_over_b0, double nu, double c[3])
{
    static int ready = 0;
    static double s[KALKER_N], lnc[3][3][KALKER_N], M[3][3][KALKER_N];
    if (!(a0_over_b0 >= 0.1 && a0_over_b0 <= 10.0 && nu >= 0.0 && nu <= 0.5)) return -1;
    if (!ready) {
        for (int i = 0; i < KALKER_N; i++) s[i] = log(KALKER_A0_OVER_B0[i]);
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) {
                for (int i = 0; i < KALKER_N; i++) lnc[k][j][i] = log(KALKER_C[k][j][i]);
                not_a_knot_spline(KALKER_N, s, lnc[k][j], M[k][j]);
            }
        ready = 1;
    }
    const double *q = KALKER_NU;
    double L[3] = {(nu - q[1]) * (nu - q[2]) / ((q[0] - q[1]) * (q[0] - q[2])),
                   (nu - q[0]) * (nu - q[2]) / ((q[1] - q[0]) * (q[1] - q[2])),
                   (nu - q[0]) * (nu - q[1]) / ((q[2] - q[0]) * (q[2] - q[1]))};
    double t = log(a0_over_b0);
    for (int k = 0; k < 3; k++) {
        double u = 0.0;
        for (int j = 0; j < 3; j++)
            u += L[j] * exp(-spline_value(KALKER_N, s, lnc[k][j], M[k][j], t));
        c[k] = 1.0 / u;
    }
    return 0;
}

/* creep_exact's coordinates (ln(a0/b0), nu, s, theta, tau) of a contact (docs/tables.md;
 * railcontact.exact_table.exact_table_coordinates):
 *   p0 = 3 N / (2 pi a0 b0),  w_sat = pi^2 (1 + nu) mu p0 / E,
 *   v = (C11 xi_x, C22 xi_y + sqrt(a0 b0) C23 phi) / w_sat,  rho = |v|,
 *   tau = phi sqrt((b0 C11)^2 + (a0 C22)^2) / w_sat,
 *   s = (2/pi) atan(rho / sqrt(1 + tau^2)),  theta = atan2(v_y, v_x).
 * Inputs: creepages xi_x, xi_y [-], spin phi [1/m], semi-axes a0 (rolling), b0 [m], Poisson's
 * ratio nu [-], normal force N [N], Young's modulus E [Pa], friction coefficient mu [-].
 * Returns 0; -1 if a0/b0 is outside [0.1, 10] or nu outside [0, 0.5] (the table's axes),
 * -2 if N, a0, b0, E or mu is not > 0. |tau| > 20 lies beyond the table's spin axis: the
 * caller checks it (the Python reader then calls the exact solver). */
static int exact_table_coordinates(double xi_x, double xi_y, double phi, double a0, double b0,
                                   double nu, double N, double E, double mu, double out[5])
{
    const double pi = 3.14159265358979323846;
    double c[3];
    if (!(N > 0.0 && a0 > 0.0 && b0 > 0.0 && E > 0.0 && mu > 0.0)) return -2;
    if (kalker_coefficients(a0 / b0, nu, c) != 0) return -1;
    double p0 = 3.0 * N / (2.0 * pi * a0 * b0);
    double w_sat = pi * pi * (1.0 + nu) * mu * p0 / E;
    double v_x = c[0] * xi_x / w_sat;
    double v_y = (c[1] * xi_y + sqrt(a0 * b0) * c[2] * phi) / w_sat;
    double tau = phi * hypot(b0 * c[0], a0 * c[1]) / w_sat;
    out[0] = log(a0 / b0);
    out[1] = nu;
    out[2] = (2.0 / pi) * atan(hypot(v_x, v_y) / sqrt(1.0 + tau * tau));
    out[3] = atan2(v_y, v_x);
    out[4] = tau;
    return 0;
}

/* --exact-coordinates: contacts on stdin (xi_x xi_y phi a0 b0 nu N E mu), coordinates out. */
static int print_exact_coordinates(void)
{
    double in[9], out[5];
    int line = 0;
    for (;;) {
        for (int k = 0; k < 9; k++)
            if (scanf("%lf", &in[k]) != 1) return 0;
        line++;
        int status = exact_table_coordinates(in[0], in[1], in[2], in[3], in[4], in[5], in[6],
                                             in[7], in[8], out);
        if (status != 0) {
            fprintf(stderr, "contact %d: %s\n", line, status == -1
                    ? "a0/b0 must be in [0.1, 10] and nu in [0, 0.5] (the table's axes)"
                    : "N, a0, b0, E and mu must be > 0");
            return 1;
        }
        printf("%.17g %.17g %.17g %.17g %.17g\n", out[0], out[1], out[2], out[3], out[4]);
    }
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "--exact-coordinates") == 0)
        return print_exact_coordinates();
    if (argc != 3) {
        fprintf(stderr, "usage: %s TABLE.nc VARIABLE < points\n"
                        "       %s --exact-coordinates < contacts\n", argv[0], argv[0]);
        return 2;
    }
    int ncid;
    CHECK(nc_open(argv[1], NC_NOWRITE, &ncid));
    int format = int_attribute(ncid, NC_GLOBAL, "railcontact_table_format");
    if ((format < 1 || format > 3) || int_attribute(ncid, NC_GLOBAL, "spline_degree") != 3) {
        fprintf(stderr, "%s: unsupported table format or spline degree\n", argv[1]);
        return 1;
    }

    /* axes and knot vectors */
    char *axes = text_attribute(ncid, NC_GLOBAL, "table_axes");
    double *knots[MAXD];
    int ncoef[MAXD], D = 0;
    for (char *name = strtok(axes, " "); name != NULL; name = strtok(NULL, " ")) {
        if (D == MAXD) { fprintf(stderr, "too many axes\n"); return 1; }
        int axis_id;
        size_t nknots;
        CHECK(nc_inq_varid(ncid, name, &axis_id));
        char *knot_name = text_attribute(ncid, axis_id, "spline_knots");
        knots[D] = read_doubles(ncid, knot_name, &nknots);
        ncoef[D] = (int)nknots - 4;
        free(knot_name);
        D++;
    }

    /* the variable's coefficients (C order: the last axis varies fastest) */
    int var_id;
    size_t ncoef_total;
    CHECK(nc_inq_varid(ncid, argv[2], &var_id));
    char *coef_name = text_attribute(ncid, var_id, "bspline_coefficients");
    double *coef = read_doubles(ncid, coef_name, &ncoef_total);
    CHECK(nc_close(ncid));
    size_t stride[MAXD];
    stride[D - 1] = 1;
    for (int d = D - 2; d >= 0; d--) stride[d] = stride[d + 1] * (size_t)ncoef[d + 1];
    if (stride[0] * (size_t)ncoef[0] != ncoef_total) {
        fprintf(stderr, "%s: coefficient array does not match the knot vectors\n", coef_name);
        return 1;
    }

    /* evaluate: 4^D coefficients per point */
    double x[MAXD], N[MAXD][4], dN[MAXD][4];
    int span[MAXD];
    for (;;) {
        for (int d = 0; d < D; d++)
            if (scanf("%lf", &x[d]) != 1) goto done;
        for (int d = 0; d < D; d++) {
            span[d] = find_span(knots[d], ncoef[d], x[d]);
            cubic_basis(knots[d], span[d], x[d], N[d], dN[d]);
        }
        double value = 0.0, grad[MAXD] = {0.0};
        int terms = 1 << (2 * D);
        for (int k = 0; k < terms; k++) {
            size_t index = 0;
            double prod = 1.0, partial[MAXD];
            for (int d = 0; d < D; d++) partial[d] = 1.0;
            for (int d = 0; d < D; d++) {
                int j = (k >> (2 * d)) & 3;
                index += (size_t)(span[d] - 3 + j) * stride[d];
                prod *= N[d][j];
                for (int e = 0; e < D; e++) partial[e] *= (e == d) ? dN[d][j] : N[d][j];
            }
            value += coef[index] * prod;
            for (int e = 0; e < D; e++) grad[e] += coef[index] * partial[e];
        }
        printf("%.17g", value);
        for (int d = 0; d < D; d++) printf(" %.17g", grad[d]);
        printf("\n");
    }
done:
    free(coef); free(coef_name); free(axes);
    for (int d = 0; d < D; d++) free(knots[d]);
    return 0;
}
