/* SPDX-License-Identifier: MIT */
/* verdict.c - one lane's answer against the exact band and the scalar answer; failures
 * printed with every input as an exact hex float, so that they reproduce anywhere. */
#include "check.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Defaults; cylcheck.c's parser (or the self-test) changes them. */
options opt = {.isa = -1,
               .category = -1,
               .only_case = -1,
               .flags_only = -1,
               .max_print = 12,
               .headline = 1};
long failures;

const char *flags_name(unsigned flags)
{
    static char buf[8][80];
    static int slot;
    char *s = buf[slot++ & 7];
    snprintf(s, 80, "0x%02x(%s%s%s%s%s)", flags, flags & CYLRAY_NORMAL ? "N" : "-",
             flags & CYLRAY_FACE_FORWARD ? "F" : "-", flags & CYLRAY_CULL_BACK ? "C" : "-",
             flags & CYLRAY_REFINE ? "R" : "-", flags & CYLRAY_FAST ? "A" : "-");
    return s;
}

static const char *part_name(int part)
{
    static char buf[4][32];
    static int slot;
    char *s = buf[slot++ & 3];
    const char *p = (part & CYLRAY_PART_MASK) == CYLRAY_SIDE     ? "side"
                    : (part & CYLRAY_PART_MASK) == CYLRAY_CAP_LO ? "cap_lo"
                    : (part & CYLRAY_PART_MASK) == CYLRAY_CAP_HI ? "cap_hi"
                                                                 : "?";
    snprintf(s, 32, "%s%s(%#x)", p, part & CYLRAY_BACKFACE ? "|back" : "", (unsigned)part);
    return s;
}

void print_case(const ref_case *rc, unsigned flags)
{
    const cylgen_case *c = &rc->c;
    const cylray_cylinder *y = &c->cyl;
    if (rc->round)
        printf("    round cone: p0 {%a, %a, %a} p1 {%a, %a, %a} r0 %a r1 %a flags %#x\n",
               (double)rc->rnd.p0[0], (double)rc->rnd.p0[1], (double)rc->rnd.p0[2],
               (double)rc->rnd.p1[0], (double)rc->rnd.p1[1], (double)rc->rnd.p1[2],
               (double)rc->rnd.r0, (double)rc->rnd.r1, rc->rnd.flags);
    else if (rc->cone)
        printf("    cone: p0 {%a, %a, %a} p1 {%a, %a, %a} r0 %a r1 %a flags %#x\n",
               (double)rc->con.p0[0], (double)rc->con.p0[1], (double)rc->con.p0[2],
               (double)rc->con.p1[0], (double)rc->con.p1[1], (double)rc->con.p1[2],
               (double)rc->con.r0, (double)rc->con.r1, rc->con.flags);
    else if (rc->sphere)
        printf("    sphere: center {%a, %a, %a} radius %a\n", (double)rc->sph.center[0],
               (double)rc->sph.center[1], (double)rc->sph.center[2], (double)rc->sph.radius);
    else
        printf("    cylinder: center {%a, %a, %a} axis {%a, %a, %a} radius %a half_height %a "
               "%s\n",
               (double)y->center[0], (double)y->center[1], (double)y->center[2],
               (double)y->axis[0], (double)y->axis[1], (double)y->axis[2], (double)y->radius,
               (double)y->half_height, (y->flags & CYLRAY_CAPPED) ? "CAPPED" : "open");
    printf("    ray: o {%a, %a, %a} d {%a, %a, %a} tmin %a tmax %a\n", (double)c->o[0],
           (double)c->o[1], (double)c->o[2], (double)c->d[0], (double)c->d[1], (double)c->d[2],
           (double)c->tmin, (double)c->tmax);
    const cylref_band *b = &rc->band[(flags & CYLRAY_CULL_BACK) != 0];
    if (b->exact.hit)
        printf("    exact:  hit t %a (%.17g) %s n {%.9g, %.9g, %.9g} (outward)\n", b->exact.t,
               b->exact.t, part_name(b->exact.part), b->exact.n[0], b->exact.n[1],
               b->exact.n[2]);
    else
        printf("    exact:  miss\n");
    printf("    band:   t [%a, %a] hit_unstable %d part_unstable %d n_spread %.3g", b->t_lo,
           b->t_hi, b->hit_unstable, b->part_unstable, b->n_spread);
    for (int i = 0; i < b->n_alt; i++)
        printf("; alt %s t [%a, %a]", part_name(b->alt[i].part), b->alt[i].t_lo,
               b->alt[i].t_hi);
    printf("\n");
}

static void print_out(const char *who, const lane_out *o, unsigned flags)
{
    if (!o->hit) {
        printf("    %s miss\n", who);
        return;
    }
    printf("    %s hit t %a (%.9g) %s", who, (double)o->t, (double)o->t, part_name(o->part));
    if (flags & CYLRAY_NORMAL)
        printf(" n {%a, %a, %a}", (double)o->n[0], (double)o->n[1], (double)o->n[2]);
    printf("\n");
}

static void fail_header(const lane_ctx *lc, const ref_case *rc)
{
    printf("FAIL %s w=%s lane %d flags %s category %s case #%d", lc->k->name, lc->width,
           lc->lane, flags_name(lc->flags), cat_name(lc->category), rc->index);
    if (lc->category == CAT_REGRESS)
        printf(" (%s)", regress_why(rc->index));
    printf(": ");
}

static void print_repro(const lane_ctx *lc, const ref_case *rc)
{
    printf("    repro: cylcheck --isa=%s --category=%s --seed=%llu --case=%d --flags=%u%s\n",
           lc->k->name, cat_name(lc->category), (unsigned long long)opt.seed, rc->index,
           lc->flags, opt.quick ? " --quick" : "");
}

void fail_memory(const lane_ctx *lc, const ref_case *rc, const char *fmt, ...)
{
    if (failures++ >= opt.max_print)
        return;
    fail_header(lc, rc);
    va_list ap;
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
    print_case(rc, lc->flags);
    print_repro(lc, rc);
}

/* A round cone's: a cap's from its sphere's center to the kernel's point, the side's
 * the tangent cone's gradient there (the cone through p0 and p1 with radii r_i /
 * cos alpha, section "Round cones" of docs/design.md), as a cone's. */
static double round_normal_of(const ref_case *rc, const lane_out *o, int ff, double n[3])
{
    const cylgen_case *c = &rc->c;
    const cylray_round_cone *q = &rc->rnd;
    double u[3], x[3], L = 0, z = 0, ww = 0, td = 0, l2 = 0;
    for (int k = 0; k < 3; k++) {
        u[k] = (double)q->p1[k] - q->p0[k];
        L += u[k] * u[k];
    }
    L = sqrt(L);
    const double dr = (double)q->r1 - q->r0, ca = sqrt((L - fabs(dr)) * (L + fabs(dr))) / L;
    const double R0 = q->r0 / ca, kk = dr / ca / L;
    const int part = o->part & CYLRAY_PART_MASK;
    const float *pc = part == CYLRAY_CAP_HI ? q->p1 : q->p0;
    for (int k = 0; k < 3; k++) {
        u[k] /= L;
        const double w = (double)c->o[k] - pc[k];
        x[k] = w + (double)o->t * c->d[k];
        z += x[k] * u[k];
        ww += w * w;
        td += (double)o->t * c->d[k] * ((double)o->t * c->d[k]);
    }
    const double rz = fabs(R0 + kk * z);
    for (int k = 0; k < 3; k++) {
        n[k] = part == CYLRAY_SIDE ? x[k] - z * u[k] - rz * kk * u[k] : x[k];
        l2 += n[k] * n[k];
    }
    const double len = sqrt(l2);
    const double sg = ((o->part & CYLRAY_BACKFACE) && ff) ? -1 / len : 1 / len;
    for (int k = 0; k < 3; k++)
        n[k] *= sg;
    /* The kernels place the spheres and the cone from the center (p0 + p1) / 2 rounded
     * to float, as the band allows t (tests/ref/rcref.h); and the cone's angle turns
     * fast close to nesting (cos alpha small): 2 ulps of a.a - dr^2 turn the side's
     * normal by about 2^-23 (L^2 + dr^2) / (L^2 cos alpha). */
    double cmax = 0, cerr = 0;
    for (int k = 0; k < 3; k++) {
        const double ck = 0.5 * ((double)q->p0[k] + q->p1[k]);
        cmax = fmax(cmax, fabs(ck));
        cerr += (double)(float)ck != ck;
    }
    const double un = 4 * cylref_float_ulp(fmax(sqrt(ww), sqrt(td))) +
                      (cerr ? 2 * cylref_float_ulp(cmax) : 0);
    if (part != CYLRAY_SIDE)
        return asin(fmin(1, un / len));
    /* The side's gradient reads the radius at the point's axial level, r(z): a point
     * off by un along the axis moves it by |k| un (k the slope, 1 / cos alpha large
     * close to nesting). */
    const double turn = 0x1p-23 * (L * L + dr * dr) / (L * L * ca);
    return 2 * asin(fmin(1, un * (1 + fabs(kk)) / len)) + turn;
}

/* The normal of the kernel's own part at the kernel's t, in double: what an excused
 * part disagreement (or an excused hit on an exact miss) is held to. Returns how far
 * that normal may legitimately turn: a side point within a few ulps of |w| and |t d|
 * from the axis (a graze of a tiny cylinder) has no direction its inputs decide. */
static double normal_of(const ref_case *rc, const lane_out *o, int ff, double n[3])
{
    const cylgen_case *c = &rc->c;
    if (rc->sphere) {
        /* The same for a sphere: the direction from the center to the kernel's point. */
        double len = 0, ww = 0, td = 0;
        for (int k = 0; k < 3; k++) {
            double w = (double)c->o[k] - rc->sph.center[k];
            n[k] = w + (double)o->t * c->d[k];
            len += n[k] * n[k];
            ww += w * w;
            td += (double)o->t * c->d[k] * ((double)o->t * c->d[k]);
        }
        len = sqrt(len);
        double s = ((o->part & CYLRAY_BACKFACE) && ff) ? -1 / len : 1 / len;
        for (int k = 0; k < 3; k++)
            n[k] *= s;
        const double u = 4 * cylref_float_ulp(fmax(sqrt(ww), sqrt(td)));
        return asin(fmin(1, u / len));
    }
    if (rc->round)
        return round_normal_of(rc, o, ff, n);
    if (rc->cone) {
        /* A cone's side: the gradient of |x_perp|^2 - r(z)^2 at the kernel's point,
         * x_perp - r(z) k u; its discs: -+u. */
        double u[3], x[3], L = 0, z = 0, ww = 0, td = 0, l2 = 0;
        for (int k = 0; k < 3; k++) {
            u[k] = (double)rc->con.p1[k] - rc->con.p0[k];
            L += u[k] * u[k];
        }
        L = sqrt(L);
        for (int k = 0; k < 3; k++) {
            u[k] /= L;
            const double w = (double)c->o[k] - rc->con.p0[k];
            x[k] = w + (double)o->t * c->d[k];
            z += x[k] * u[k];
            ww += w * w;
            td += (double)o->t * c->d[k] * ((double)o->t * c->d[k]);
        }
        /* |r|: a point that rounding puts a hair past an apex is on the cone's own
         * nappe, whose normal the kernels give (kernel/store.h), not the mirror's */
        const double kk = ((double)rc->con.r1 - rc->con.r0) / L, rz = fabs(rc->con.r0 + kk * z);
        const int part = o->part & CYLRAY_PART_MASK;
        for (int k = 0; k < 3; k++) {
            n[k] = part == CYLRAY_SIDE     ? x[k] - z * u[k] - rz * kk * u[k]
                   : part == CYLRAY_CAP_LO ? -u[k]
                                           : u[k];
            l2 += n[k] * n[k];
        }
        const double len = sqrt(l2);
        const double sg = ((o->part & CYLRAY_BACKFACE) && ff) ? -1 / len : 1 / len;
        for (int k = 0; k < 3; k++)
            n[k] *= sg;
        if (part != CYLRAY_SIDE)
            return 0;
        /* Near the apex the normal may turn all the way round the axis. */
        const double un = 4 * cylref_float_ulp(fmax(sqrt(ww), sqrt(td)));
        return 2 * asin(fmin(1, un / len));
    }
    double v[3], p[3], vv = 0, pv = 0, len = 0;
    for (int k = 0; k < 3; k++) {
        v[k] = c->cyl.axis[k];
        p[k] = (double)c->o[k] - (double)c->cyl.center[k] + (double)o->t * c->d[k];
        vv += v[k] * v[k];
        pv += p[k] * v[k];
    }
    int part = o->part & CYLRAY_PART_MASK;
    for (int k = 0; k < 3; k++) {
        n[k] = part == CYLRAY_SIDE     ? p[k] - pv / vv * v[k]
               : part == CYLRAY_CAP_LO ? -v[k]
                                       : v[k];
        len += n[k] * n[k];
    }
    len = sqrt(len);
    double s = ((o->part & CYLRAY_BACKFACE) && ff) ? -1 / len : 1 / len;
    double ww = 0, td = 0;
    for (int k = 0; k < 3; k++) {
        n[k] *= s;
        ww += ((double)c->o[k] - c->cyl.center[k]) * ((double)c->o[k] - c->cyl.center[k]);
        td += (double)o->t * c->d[k] * ((double)o->t * c->d[k]);
    }
    if (part != CYLRAY_SIDE)
        return 0;
    const double u = 4 * cylref_float_ulp(fmax(sqrt(ww), sqrt(td)));
    return asin(fmin(1, u / len));
}

/* Appends one reason to the failure message: a lane can fail several ways at once. */
static void add_reason(char *why, size_t size, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void add_reason(char *why, size_t size, const char *fmt, ...)
{
    size_t len = strlen(why);
    if (len && len + 2 < size) {
        memcpy(why + len, "; ", 3);
        len += 2;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why + len, size - len, fmt, ap);
    va_end(ap);
}

void check_lane(const lane_ctx *lc, const ref_case *rc, const lane_out *got,
                const lane_out *scalar)
{
    const unsigned flags = lc->flags;
    const cylref_band *b = &rc->band[(flags & CYLRAY_CULL_BACK) != 0];
    const int mode = mode_of(flags);
    stat_cell *s = stat_at(lc->k->isa, lc->category, mode);
    const double tol = mode == MODE_FAST ? TOL_T_ULPS_FAST : TOL_T_ULPS;
    char why[480] = "";

    s->lanes++;
    s->exact_hits += b->exact.hit;
    s->kernel_hits += got->hit;
    double ub = 0;
    int v = cylref_judge(b, got->hit, got->part, got->t, &ub);
    if (got->hit != b->exact.hit) {
        if (v) {
            s->hm_unexcused++;
            add_reason(why, sizeof why, "%s where the exact answer is a stable %s",
                       got->hit ? "hit" : "miss", got->hit ? "miss" : "hit");
        } else {
            s->hm_excused++;
        }
    } else if (got->hit && got->part != b->exact.part) {
        if (v) {
            s->part_unexcused++;
            add_reason(why, sizeof why, "part %s where only %s is possible",
                       part_name(got->part), part_name(b->exact.part));
        } else {
            s->part_excused++;
        }
    }
    if (got->hit && !v) {
        if (ub > s->max_beyond)
            s->max_beyond = ub;
        if (!(ub <= tol)) {
            s->t_beyond++;
            add_reason(why, sizeof why, "t %.3g ulps outside the band (tolerance %g)", ub, tol);
        }
    }
    if (got->hit && b->exact.hit && got->part == b->exact.part) {
        double u = cylref_ulps(got->t, b->exact.t);
        stat_add_ulps(s, u);
        if (opt.show_ulps > 0 && u > opt.show_ulps) {
            printf("NOTE %s w=%s lane %d flags %s category %s case #%d: t %.3g ulps from exact "
                   "(%.3g beyond the band)\n",
                   lc->k->name, lc->width, lc->lane, flags_name(flags), cat_name(lc->category),
                   rc->index, u, ub);
            print_case(rc, flags);
            print_out("kernel:", got, flags);
        }
    }

    if (got->hit && !v && (flags & CYLRAY_NORMAL)) {
        const float *n = got->n;
        double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        double lerr = fabs(len - 1);
        if (!(lerr <= s->max_len))
            s->max_len = lerr == lerr ? lerr : INFINITY;
        if (!(lerr <= TOL_NORMAL_LEN))
            add_reason(why, sizeof why, "|n| - 1 = %.3g (tolerance %g)", len - 1,
                       TOL_NORMAL_LEN);
        double e[3], spread = b->n_spread;
        int ff = (flags & CYLRAY_FACE_FORWARD) != 0;
        if (got->part == b->exact.part) {
            double sg = (ff && (got->part & CYLRAY_BACKFACE)) ? -1 : 1;
            for (int k = 0; k < 3; k++)
                e[k] = sg * b->exact.n[k];
        } else {
            spread = fmax(spread, normal_of(rc, got, ff, e));
        }
        double ang = cylref_angle(n, e), excess = ang - spread;
        if (!(ang <= s->max_angle))
            s->max_angle = ang;
        if (!(excess <= s->max_angle_excess))
            s->max_angle_excess = excess;
        if (!(excess <= TOL_NORMAL_ANGLE))
            snprintf(why, sizeof why,
                     "normal %.3g rad from the exact one, %.3g beyond the band (tolerance %g)",
                     ang, excess, TOL_NORMAL_ANGLE);
    }

    if (lc->category == CYLGEN_RIM && b->exact.hit) {
        s->rim_rays++;
        if (!got->hit)
            s->rim_missed++;
        else if ((got->part & CYLRAY_BACKFACE) != (b->exact.part & CYLRAY_BACKFACE) ||
                 ((double)got->t > b->t_hi && ub > tol))
            s->rim_later++;
    }

    if (scalar) {
        s->vs_scalar++;
        if (scalar->hit == got->hit &&
            (!got->hit ||
             (memcmp(&scalar->t, &got->t, sizeof got->t) == 0 && scalar->part == got->part &&
              memcmp(scalar->n, got->n, sizeof got->n) == 0)))
            s->same_as_scalar++;
        if (scalar->hit != got->hit || (got->hit && scalar->part != got->part))
            s->scalar_hm++;
        else if (got->hit) {
            /* In ulps of the larger of the two: a self-hit near t = 0 is not 1e30 ulps. */
            double big = fmax(fabs((double)got->t), fabs((double)scalar->t));
            double d = fabs((double)got->t - (double)scalar->t) / cylref_float_ulp(big);
            if (d > s->max_vs_scalar)
                s->max_vs_scalar = d;
        }
    }

    if (!why[0])
        return;
    if (failures++ >= opt.max_print)
        return;
    fail_header(lc, rc);
    printf("%s\n", why);
    print_case(rc, flags);
    print_out("kernel:", got, flags);
    if (scalar)
        print_out("scalar:", scalar, flags);
    print_repro(lc, rc);
}
