/* SPDX-License-Identifier: MIT */
/* guard_selftest.c - the guarded runner (guarded.c) catches what it claims to: a fake
 * kernel table wraps the scalar path and breaks one rule of the contract at a time;
 * each must be reported, and the faithful wrapper must not be. Without this, a runner
 * that checked nothing would let every other test pass. */
#include <math.h>
#include <string.h>

#include "cylray.h"
#include "guarded.h"
#include "tcheck.h"

#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif

enum fault {
    F_NONE,           /* faithful: no violation may be reported */
    F_INACTIVE_WRITE, /* writes t of an inactive lane */
    F_INACTIVE_BIT,   /* reports an inactive lane as hit */
    F_MISS_WRITE,     /* writes part of an active lane that missed */
    F_TMAX,           /* tmax one ulp off t */
    F_NORMAL,         /* writes a normal without CYLRAY_NORMAL */
    F_INPUT,          /* changes an input field */
    F_T_RANGE,        /* reports t below tmin */
    F_PART,           /* reports part 0 for a hit */
    F_COUNT,          /* stream: returns one hit too many */
    F_CANARY,         /* writes one float past the end (skipped under ASan, which
                          would stop the process at the write itself) */
    F_NFAULT
};
static const char *const fault_name[F_NFAULT] = {
    "none",  "inactive write", "inactive bit", "miss write", "tmax",  "normal",
    "input", "t range",        "part",         "count",      "canary"};

static enum fault fault;
static const cylray_kernels *real;

static uint32_t fake4(const cylray_prepared *P, cylray_ray4 *r, cylray_hit4 *h, uint32_t a,
                      unsigned fl)
{
    uint32_t m = real->intersect4(P, r, h, a, fl);
    switch (fault) {
    case F_INACTIVE_WRITE:
        h->t[2] = 1;
        break;
    case F_INACTIVE_BIT:
        m |= 4u;
        break;
    case F_MISS_WRITE:
        h->part[1] = CYLRAY_SIDE;
        break;
    case F_TMAX:
        r->tmax[0] = nextafterf(r->tmax[0], INFINITY);
        break;
    case F_NORMAL:
        h->nx[0] = 0;
        break;
    case F_INPUT:
        r->oy[3] += 1;
        break;
    case F_T_RANGE:
        h->t[0] = r->tmax[0] = r->tmin[0] - 1;
        break;
    case F_PART:
        h->part[0] = 0;
        break;
    case F_CANARY:
        ((float *)(void *)h)[5 * 4] = 0;
        break;
    default:
        break;
    }
    return m;
}

static size_t fake_stream(const cylray_prepared *P, const cylray_rays *r, const cylray_hits *h,
                          size_t n, unsigned fl)
{
    size_t c = real->intersect_stream(P, r, h, n, fl);
    switch (fault) {
    case F_MISS_WRITE:
        h->part[1] = CYLRAY_SIDE;
        break;
    case F_TMAX:
        r->tmax[0] = nextafterf(r->tmax[0], INFINITY);
        break;
    case F_INPUT:
        ((float *)(uintptr_t)r->oy)[3] += 1;
        break;
    case F_COUNT:
        c++;
        break;
    case F_CANARY:
        h->t[n] = 0;
        break;
    default:
        break;
    }
    return c;
}

int main(void)
{
    real = cylray_kernels_for(CYLRAY_ISA_SCALAR);
    cylray_kernels fake = *real;
    fake.name = "fake";
    fake.intersect4 = fake4;
    fake.intersect_stream = fake_stream;

    const cylray_cylinder c = {{0, 0, 0}, {0, 0, 1}, 1, 2, CYLRAY_CAPPED};
    cylray_prepared P;
    cylray_prepare(&P, &c);
    /* lane 0 hits, lane 1 misses, lane 2 would hit but is inactive, lane 3 hits */
    gbatch b;
    const float rays[4][8] = {{-5, 0, 0, 1, 0, 0, 0, 100},
                              {-5, 3, 0, 1, 0, 0, 0, 100},
                              {-5, 0, 1, 1, 0, 0, 0, 100},
                              {-5, 0.5f, -1, 1, 0, 0, 0, 100}};
    for (int i = 0; i < 4; i++)
        for (int f = 0; f < G_NFIELD; f++)
            b.f[f][i] = rays[i][f];

    for (int f = 0; f < F_NFAULT; f++) {
        fault = (enum fault)f;
#ifdef UNDER_ASAN
        if (fault == F_CANARY)
            continue;
#endif
        gresult r;
        const long before = tc_failures_;
        tc_silent_ = 1;
        int vp = fault == F_COUNT ? 0 : g_intersect(&fake, 4, &P, &b, 4, 0xbu, 0, 0, &r);
        int vs = g_intersect(&fake, G_STREAM, &P, &b, 4, 0, 0, 1, &r);
        tc_silent_ = 0;
        const long caught = tc_failures_ - before;
        tc_failures_ = before;
        if (fault == F_NONE) {
            CHECK(vp == 0 && vs == 0 && caught == 0,
                  "the faithful wrapper was reported (%d, %d violations)", vp, vs);
            continue;
        }
        /* The packet faults must show in the packet run; the stream ones in the stream
         * run (inactive lanes do not exist there). */
        const int packet_fault = fault != F_COUNT;
        const int stream_fault = fault == F_MISS_WRITE || fault == F_TMAX || fault == F_INPUT ||
                                 fault == F_COUNT || fault == F_CANARY;
        CHECK(!packet_fault || vp > 0, "packet fault \"%s\" went unnoticed", fault_name[f]);
        CHECK(!stream_fault || vs > 0, "stream fault \"%s\" went unnoticed", fault_name[f]);
        CHECK(caught == vp + vs, "fault \"%s\": %ld failures counted for %d violations",
              fault_name[f], caught, vp + vs);
    }
    return tc_report("api-guard-selftest");
}
