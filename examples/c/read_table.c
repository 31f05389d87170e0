/*
 * read_table.c: evaluate a railcontact table (the tables/ folder) from C with netCDF-C.
 *
 * Reads only what the file documents in its attributes:
 *   global  table_axes         axis names, space separated, in the order of the coefficient dims
 *   global  spline_degree      degree p of the tensor-product B-spline (3: cubic, C2)
 *   <axis>  spline_knots       name of that axis' knot vector variable (length n_coef + p + 1)
 *   <var>   bspline_coefficients  name of the coefficient variable, dims = one per axis
 * and evaluates value = sum_i c[i1..iD] prod_d B_{d,i_d}(x_d) and the D first partial
 * derivatives at each point read from standard input (D numbers per line, in table_axes order).
 * Points must lie inside the axes' node range (clamped to the knot range otherwise).
 *
 * Build:  gcc -O2 -o read_table read_table.c -lnetcdf -lm
 * Use:    ./read_table ../../tables/creep_modified_strip.nc force_ratio < points.txt
 * Prints one line per point: value d/dx_1 ... d/dx_D (%.17g).
 *
 * The basis functions and their derivatives follow The NURBS Book (Piegl and Tiller, 1997),
 * Algorithms A2.1 (span) and A2.3 (basis function derivatives). MIT licence, as railcontact.
 */
#include <netcdf.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DIMS 8
#define MAX_DEG 5

static void check(int status, const char *what)
{
    if (status != NC_NOERR) {
        fprintf(stderr, "read_table: %s: %s\n", what, nc_strerror(status));
        exit(2);
    }
}

/* A text attribute as a NUL-terminated string (caller frees). */
static char *text_attribute(int nc, int var, const char *name)
{
    size_t len;
    nc_type type;
    check(nc_inq_att(nc, var, name, &type, &len), name);
    if (type != NC_CHAR) {
        fprintf(stderr, "read_table: attribute %s is not text\n", name);
        exit(2);
    }
    char *s = calloc(len + 1, 1);
    check(nc_get_att_text(nc, var, name, s), name);
    return s;
}

/* An integer attribute, stored as a number or as text. */
static int int_attribute(int nc, int var, const char *name)
{
    nc_type type;
    size_t len;
    check(nc_inq_att(nc, var, name, &type, &len), name);
    if (type == NC_CHAR) {
        char *s = text_attribute(nc, var, name);
        int v = atoi(s);
        free(s);
        return v;
    }
    int v;
    check(nc_get_att_int(nc, var, name, &v), name);
    return v;
}

/* Knot span i with t[i] <= x < t[i+1], p <= i <= n_coef - 1 (A2.1; x clamped). */
static int find_span(const double *t, int n_coef, int p, double x)
{
    int lo = p, hi = n_coef;
    if (x >= t[hi]) return hi - 1;
    if (x <= t[lo]) return lo;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (t[mid] <= x) lo = mid; else hi = mid;
    }
    return lo;
}

/* ders[k][j]: k-th derivative (k = 0, 1) of the non-zero basis function N_{span-p+j,p}(x)
 * (A2.3 with n = 1). */
static void basis_ders(const double *t, int span, int p, double x, double ders[2][MAX_DEG + 1])
{
    double ndu[MAX_DEG + 1][MAX_DEG + 1], left[MAX_DEG + 1], right[MAX_DEG + 1];
    ndu[0][0] = 1.0;
    for (int j = 1; j <= p; j++) {
        left[j] = x - t[span + 1 - j];
        right[j] = t[span + j] - x;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            ndu[j][r] = right[r + 1] + left[j - r];
            double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    for (int j = 0; j <= p; j++) {
        ders[0][j] = ndu[j][p];
        /* first derivative: p (N_{j,p-1}/(t[j+p]-t[j]) - N_{j+1,p-1}/(t[j+p+1]-t[j+1])) */
        double d = 0.0;
        if (j >= 1) d += ndu[j - 1][p - 1] / ndu[p][j - 1];
        if (j <= p - 1) d -= ndu[j][p - 1] / ndu[p][j];
        ders[1][j] = p * d;
    }
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s TABLE.nc VARIABLE < points\n", argv[0]);
        return 2;
    }
    int nc, var, coef_var;
    check(nc_open(argv[1], NC_NOWRITE, &nc), argv[1]);
    check(nc_inq_varid(nc, argv[2], &var), argv[2]);
    int p = int_attribute(nc, NC_GLOBAL, "spline_degree");
    if (p < 1 || p > MAX_DEG) {
        fprintf(stderr, "read_table: spline_degree %d not in 1..%d\n", p, MAX_DEG);
        return 2;
    }

    /* axes, in table_axes order, and their knot vectors */
    char *axes = text_attribute(nc, NC_GLOBAL, "table_axes");
    int ndim = 0;
    double *knots[MAX_DIMS];
    int n_coef[MAX_DIMS];
    for (char *name = strtok(axes, " "); name; name = strtok(NULL, " ")) {
        if (ndim == MAX_DIMS) { fprintf(stderr, "read_table: too many axes\n"); return 2; }
        int axis_var, knot_var, knot_dim;
        size_t n_knots;
        check(nc_inq_varid(nc, name, &axis_var), name);
        char *knot_name = text_attribute(nc, axis_var, "spline_knots");
        check(nc_inq_varid(nc, knot_name, &knot_var), knot_name);
        check(nc_inq_vardimid(nc, knot_var, &knot_dim), knot_name);
        check(nc_inq_dimlen(nc, knot_dim, &n_knots), knot_name);
        knots[ndim] = malloc(n_knots * sizeof(double));
        check(nc_get_var_double(nc, knot_var, knots[ndim]), knot_name);
        n_coef[ndim] = (int)n_knots - p - 1;
        free(knot_name);
        ndim++;
    }

    /* coefficients: C order, one dimension per axis, last axis fastest */
    char *coef_name = text_attribute(nc, var, "bspline_coefficients");
    check(nc_inq_varid(nc, coef_name, &coef_var), coef_name);
    int coef_ndims;
    check(nc_inq_varndims(nc, coef_var, &coef_ndims), coef_name);
    size_t total = 1;
    long stride[MAX_DIMS];
    for (int d = ndim - 1; d >= 0; d--) { stride[d] = (long)total; total *= (size_t)n_coef[d]; }
    if (coef_ndims != ndim) {
        fprintf(stderr, "read_table: %s has %d dims, table_axes %d\n", coef_name, coef_ndims,
                ndim);
        return 2;
    }
    double *coef = malloc(total * sizeof(double));
    check(nc_get_var_double(nc, coef_var, coef), coef_name);
    check(nc_close(nc), argv[1]);

    double x[MAX_DIMS], ders[MAX_DIMS][2][MAX_DEG + 1];
    int span[MAX_DIMS];
    for (;;) {
        for (int d = 0; d < ndim; d++)
            if (scanf("%lf", &x[d]) != 1) goto done;
        for (int d = 0; d < ndim; d++) {
            span[d] = find_span(knots[d], n_coef[d], p, x[d]);
            basis_ders(knots[d], span[d], p, x[d], ders[d]);
        }
        /* sum over the (p+1)^D touched coefficients; out[0] value, out[1+k] d/dx_k */
        double out[MAX_DIMS + 1] = {0.0};
        int idx[MAX_DIMS] = {0};
        for (;;) {
            long flat = 0;
            for (int d = 0; d < ndim; d++) flat += (span[d] - p + idx[d]) * stride[d];
            double c = coef[flat];
            for (int k = -1; k < ndim; k++) {
                double w = 1.0;
                for (int d = 0; d < ndim; d++) w *= ders[d][d == k][idx[d]];
                out[k + 1] += w * c;
            }
            int d = ndim - 1;
            while (d >= 0 && ++idx[d] > p) idx[d--] = 0;
            if (d < 0) break;
        }
        for (int k = 0; k <= ndim; k++) printf(k ? " %.17g" : "%.17g", out[k]);
        printf("\n");
    }
done:
    free(coef);
    free(coef_name);
    free(axes);
    for (int d = 0; d < ndim; d++) free(knots[d]);
    return 0;
}
