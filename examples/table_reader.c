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
 */
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

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s TABLE.nc VARIABLE < points\n", argv[0]);
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
