"""Stability cases for implicit-surface intersection: scenes, rays and analytic answers.

Each case is one small scene and a list of rays, each ray with an expectation derived
from closed forms or from a one-dimensional solve of the kernel formula written out here
(never from the program under test):

  Hit(t, allow)     the first hit is at parameter t (units of the given direction),
                    |t_got - t|·|d| <= allow (object-space distance);
  Miss()            no hit;
  Either(t, allow)  the tangency policy of libray/libobj/implicit/README.md ("Guarantee"):
                    a hit is reported only where a sign change of F - T is observed, so an
                    exact tangency is a miss or, through rounding, a hit at the tangent point.

The allowance of a hit is the scene's `tolerance` (the root accuracy every method promises)
plus the rounding of the input itself: ROUNDING_ULPS spacings of doubles at the largest
coordinate involved, and, where the ray meets the surface at a small angle, the field's
rounding (FIELD_ROUNDING) divided by the slope of F along the ray. Hits must also carry a
finite unit normal; where the normal is known analytically it is checked to NORMAL_ALLOW.

Field model (the module's README): F(p) = sum_i w_i f_i(|p - c_i|), surface F = T.
Kernels: Gascuel quadratic (e, k, R) and Rayshade's blob (s, R).
"""
import math
from decimal import Decimal, getcontext
from fractions import Fraction

getcontext().prec = 50

TOLERANCE = 1e-9        # the `tolerance` written into every scene
ROUNDING_ULPS = 32      # spacing of doubles allowed at the largest coordinate of a ray
FIELD_ROUNDING = 1e-15  # absolute rounding of a field value near T (a few ulps of 1)
NORMAL_ALLOW = 1e-6     # |n_got - n_expected| where the normal is known
SURFACE = "surface s diffuse 1 1 1\n"


# --- kernels and the field model -------------------------------------------------------

def quadratic(e, k, radius):
    """Gascuel's kernel, quadratic inner part; outer part in Hermite form."""
    ell = radius - e
    m = k * ell

    def f(r):
        if r <= e:
            return 1 + k * e / 2 - k * r * r / (2 * e)
        if r >= radius:
            return 0 * r
        s = (r - e) / ell
        return (2 * s ** 3 - 3 * s ** 2 + 1) - m * (s ** 3 - 2 * s ** 2 + s)
    f.spec = "quadratic %r %r %r" % (e, k, radius)
    return f


def blob(strength, radius):
    def f(r):
        if r >= radius:
            return 0 * r
        u = 1 - r * r / (radius * radius)
        return strength * u * u
    f.spec = "blob %r %r" % (strength, radius)
    return f


class Skeleton:
    def __init__(self, name, centre, kernel, weight=1):
        self.name, self.centre, self.kernel, self.weight = name, centre, kernel, weight


def bisect(g, lo, hi, steps=200):
    """Root of g on [lo, hi] (g(lo), g(hi) of opposite signs), to the working precision
    of the numbers given (float or Decimal)."""
    glo = g(lo)
    for _ in range(steps):
        mid = (lo + hi) / 2
        if mid in (lo, hi):
            break
        gm = g(mid)
        if (gm > 0) == (glo > 0):
            lo, glo = mid, gm
        else:
            hi = mid
    return (lo + hi) / 2


def quadratic_distance_for(e, k, radius, value):
    """r with f(r) = value for the quadratic kernel (0 < value <= 1: the outer part),
    solved in 50-digit decimals: the outer part is monotone on [e, R], and f(e) = 1."""
    if value == 1:
        return Decimal(repr(e))
    f = quadratic(Decimal(repr(e)), Decimal(repr(k)), Decimal(repr(radius)))
    v = Decimal(repr(value)) if not isinstance(value, Decimal) else value
    return bisect(lambda r: f(r) - v, Decimal(repr(e)), Decimal(repr(radius)), 400)


# --- rays and expectations -------------------------------------------------------------

class Hit:
    """normal_allow: NORMAL_ALLOW plus the angle a position error of `allow` makes on a
    surface of radius of curvature `curvature_radius` (tiny spheres)."""

    def __init__(self, t, allow, normal=None, patch=None, curvature_radius=1.0):
        self.t, self.allow, self.normal, self.patch = t, allow, normal, patch
        self.normal_allow = NORMAL_ALLOW + allow / curvature_radius
        self.alternatives = []  # other acceptable (normal, patch) pairs, at a crease


class Miss:
    pass


class Either:
    def __init__(self, t, allow):
        self.t, self.allow = t, allow


class Ray:
    def __init__(self, label, o, d, expect, tmin=None, tmax=None):
        self.label, self.o, self.d, self.expect = label, tuple(o), tuple(d), expect
        self.tmin, self.tmax = tmin, tmax

    def line(self):
        words = [repr(float(x)) for x in self.o + self.d]
        if self.tmin is not None or self.tmax is not None:
            words.append(repr(float(self.tmin or 0.0)))
        if self.tmax is not None:
            words.append(repr(float(self.tmax)))
        return " ".join(words)


class Case:
    def __init__(self, name, category, expectation, scene, rays):
        self.name, self.category, self.expectation = name, category, expectation
        self.scene, self.rays = scene, rays


def implicit_object(name, skeletons, threshold=1.0, blends=(), contacts=(), propagations=()):
    """contacts: pairs of skeleton names; propagations: (name, width[, height]) tuples."""
    lines = ["name %s implicit s\n tolerance %r threshold %r\n" % (name, TOLERANCE, threshold)]
    for s in skeletons:
        lines.append(" point %s %r %r %r weight %r field %s\n"
                     % ((s.name,) + tuple(float(c) for c in s.centre) + (float(s.weight),
                                                                        s.kernel.spec)))
    lines += [" blend %s\n" % " ".join(b) for b in blends]
    lines += [" contact %s %s\n" % pair for pair in contacts]
    lines += [" propagation %s\n" % " ".join(map(str, p)) for p in propagations]
    lines.append("end\nobject %s\n" % name)
    return "".join(lines)


def scene_of(*objects):
    return SURFACE + "".join(objects)


# --- vector helpers --------------------------------------------------------------------

def add(a, b, s=1.0):
    return tuple(x + s * y for x, y in zip(a, b))


def scale(a, s):
    return tuple(s * x for x in a)


def unit(a):
    n = math.sqrt(sum(x * x for x in a))
    return tuple(x / n for x in a)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def ulp_at(*values):
    return math.ulp(max(abs(float(v)) for v in values))


def sphere_roots(o, d, c, radius):
    """Both parameters where the line o + t·d meets the sphere, from the rays' actual
    (rounded) numbers in exact rational arithmetic; the square root in 50 digits.
    None when the line misses or touches."""
    oc = [Fraction(a) - Fraction(b) for a, b in zip(o, c)]
    dd = [Fraction(x) for x in d]
    a = sum(x * x for x in dd)
    b = sum(x * y for x, y in zip(oc, dd))
    q = sum(x * x for x in oc) - Fraction(radius) ** 2
    disc = b * b - a * q
    if disc <= 0:
        return None
    root = (Decimal(disc.numerator) / Decimal(disc.denominator)).sqrt()
    bd = Decimal(b.numerator) / Decimal(b.denominator)
    ad = Decimal(a.numerator) / Decimal(a.denominator)
    return float((-bd - root) / ad), float((-bd + root) / ad)


def sphere_hit(o, d, c, radius, tmin=0.0, slope=None, solid_outside=False):
    """The first sphere root above tmin as a Hit with the solid's outward normal there
    (pointing away from the centre, or towards it when the solid lies outside the sphere,
    as around a cavity). The allowance adds the field's rounding over the slope of F along
    the unit ray when the caller gives |∇F| on the surface (`slope`), for grazing rays."""
    t0, t1 = sphere_roots(o, d, c, radius)
    t = t0 if t0 > tmin else t1
    p = add(o, d, t)
    normal = unit(add(p, c, -1) if not solid_outside else add(c, p, -1))
    dn = unit(d)
    cosine = abs(sum(x * y for x, y in zip(normal, dn)))
    allow = TOLERANCE + ROUNDING_ULPS * ulp_at(*(o + c))
    if slope:
        allow += FIELD_ROUNDING / (slope * max(cosine, 1e-300))
    return Hit(t, allow, normal, curvature_radius=radius)


def frame(v):
    """A unit vector along v and two unit vectors completing an orthonormal frame."""
    v = unit(v)
    w = unit(cross(v, (0.3, -0.7, 0.2)))
    return v, w, cross(v, w)


# --- the cases -------------------------------------------------------------------------

UNIT_QUADRATIC = quadratic(1.0, 1.0, 2.0)  # lone point: sphere of radius e = 1; |∇F| = k = 1
UNIT_BLOB = blob(1.0, 2.0)                  # at T = 0.5625 = 0.75²: radius R·sqrt(1 - 0.75) = 1
BLOB_THRESHOLD = 0.5625
BLOB_SLOPE = 0.75                           # |f'(1)| = 4s·r/R²·(1 - r²/R²) = 4·1/4·3/4
DELTAS = (1e-3, 1e-5, 1e-7, 1e-9)
CENTRE = (0.25, -0.5, 0.125)


def unit_sphere_scene(kernel):
    threshold = BLOB_THRESHOLD if kernel is UNIT_BLOB else 1.0
    return scene_of(implicit_object("ball", [Skeleton("c", CENTRE, kernel)], threshold))


def grazing(kernel, inside):
    slope = BLOB_SLOPE if kernel is UNIT_BLOB else 1.0
    rays = []
    for direction in ((1, 2, 0.5), (0, 0, 1)):
        v, w, _ = frame(direction)
        for delta in DELTAS:
            b = 1 - delta if inside else 1 + delta
            o = add(add(CENTRE, v, -5), w, b)
            label = "dir %s, b = 1%s%g" % (direction, "-" if inside else "+", delta)
            expect = sphere_hit(o, v, CENTRE, 1.0, slope=slope) if inside else Miss()
            rays.append(Ray(label, o, v, expect))
    return rays


def tangency(kernel):
    """Lines at distance exactly 1 (to the rounding of their numbers) from the centre. On
    the tangent line F - T = -k·x²/(2e) (quadratic) with x the distance from the tangent
    point, so rounding of F (FIELD_ROUNDING) can make F >= T only within
    x <= sqrt(2e·FIELD_ROUNDING/k) ≈ 4.5e-8 of it: a reported hit must lie that close."""
    near = math.sqrt(2 * FIELD_ROUNDING) + TOLERANCE
    rays = []
    for direction in ((1, 0, 0), (1, 2, 0.5), (-0.3, 0.1, 1)):
        v, w, u = frame(direction)
        for side in (w, u):
            for back, tmax in ((5.0, None), (1e-3, None), (5.0, 5.5)):
                o = add(add(CENTRE, v, -back), side, 1.0)
                label = "dir %s, tangent point at t = %g%s" % (
                    direction, back, "" if tmax is None else ", tmax %g" % tmax)
                rays.append(Ray(label, o, v, Either(back, near), tmax=tmax))
    return rays


def far_camera(kernel):
    """Camera at distance D along v, line passing 0.5 from the centre; and the whole scene
    translated by D with a near camera. Allowance: ROUNDING_ULPS spacings at D."""
    slope = BLOB_SLOPE if kernel is UNIT_BLOB else 1.0
    v, w, _ = frame((1, 2, 0.5))
    rays = []
    for distance in (1e3, 1e4, 1e5, 1e6, 1e7):
        o = add(add(CENTRE, v, -distance), w, 0.5)
        rays.append(Ray("camera at D = %g" % distance, o, v,
                        sphere_hit(o, v, CENTRE, 1.0, slope=slope)))
    return rays


def far_scene_case():
    rays = []
    objects = []
    v, w, _ = frame((1, 2, 0.5))
    for i, offset in enumerate((1e3, 1e5, 1e7)):
        c = (offset, -offset, 0.5 * offset)
        objects.append(implicit_object("far%d" % i, [Skeleton("c", c, UNIT_QUADRATIC)]))
        o = add(add(c, v, -5), w, 0.5)
        rays.append(Ray("sphere centred at %s, camera 5 away" % (c,), o, v,
                        sphere_hit(o, v, c, 1.0, slope=1.0)))
    return scene_of(*objects), rays


def inside_camera():
    rays = []
    for q, direction in (((0, 0, 0), (0, 0, 3)), ((0, 0, 0), (1, 2, 0.5)),
                         ((0.5, 0.1, -0.2), (-1, 0.3, 0.2)), ((0.1, 0.9, 0), (0, 1, 0)),
                         ((0, 0.999, 0), (1, 0, 0))):
        o = add(CENTRE, q)
        rays.append(Ray("origin centre+%s, dir %s" % (q, direction), o, direction,
                        sphere_hit(o, direction, CENTRE, 1.0, tmin=0.0, slope=1.0)))
    return rays


def secondary():
    """Origins a hair h from the unit sphere along the unit vector n."""
    n, w, _ = frame((1, 2, 3))
    rays = []
    for h in (1e-3, 1e-6, 1e-9):
        for sign in (1, -1):
            o = add(CENTRE, n, 1 + sign * h)
            where = "outside" if sign > 0 else "inside"
            out = Miss() if sign > 0 else sphere_hit(o, n, CENTRE, 1.0)
            rays.append(Ray("%s by %g, outward" % (where, h), o, n, out))
            rays.append(Ray("%s by %g, inward" % (where, h), o, scale(n, -1),
                            sphere_hit(o, scale(n, -1), CENTRE, 1.0)))
    o = add(CENTRE, n)
    off = 1e-5  # the renderer's style of secondary-ray offset
    rays.append(Ray("on the surface, outward, tmin 1e-5", o, n, Miss(), tmin=off))
    rays.append(Ray("on the surface, tangential, tmin 1e-5", o, w, Miss(), tmin=off))
    for theta in (0.0, 0.5, 1.2):
        d = add(scale(n, -math.cos(theta)), w, math.sin(theta))
        rays.append(Ray("on the surface, %g rad from the inward normal, tmin 1e-5" % theta,
                        o, d, sphere_hit(o, d, CENTRE, 1.0, tmin=off, slope=1.0), tmin=off))
    return rays


# Two equal quadratic points (e = 1, k = 1, R = 2, so m = 1 and the outer part is
# (1 - s)²(1 + s) with s = r - 1) at (±a, 0, 0). On the bisecting plane F = 2f(sqrt(a² + ρ²)),
# so the neck radius is sqrt(D_HALF² - a²) where f(D_HALF) = 1/2.
D_HALF = quadratic_distance_for(1.0, 1.0, 2.0, Decimal("0.5"))


def two_points(name, a, z=0.0):
    return implicit_object(name, [Skeleton("a", (-a, 0.0, z), UNIT_QUADRATIC),
                                  Skeleton("b", (a, 0.0, z), UNIT_QUADRATIC)])


def neck_radius(a):
    return float((D_HALF * D_HALF - Decimal(repr(a)) ** 2).sqrt())


def neck_allow(a, rho):
    """Along a midplane ray F = 2f(sqrt(a² + y²)); at y = ρ its slope is 2|f'(d)|ρ/d, and
    the rounding of a² + y² (an ulp of a²) moves the root by that over 2ρ."""
    d = float(D_HALF)
    slope = 2 * abs(derivative(UNIT_QUADRATIC, d)) * rho / d
    return (TOLERANCE + ROUNDING_ULPS * ulp_at(5.0) + FIELD_ROUNDING / slope
            + 4 * math.ulp(a * a) / (2 * rho))


def derivative(f, r, h=1e-6):
    return (f(r + h) - f(r - h)) / (2 * h)


def necks():
    objects, rays = [], []
    for i, rho in enumerate((1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6)):
        a = float((D_HALF * D_HALF - Decimal(repr(rho)) ** 2).sqrt())
        z = 10.0 * i
        objects.append(two_points("neck%d" % i, a, z))
        r = neck_radius(a)
        o = (0.0, -5.0, z)
        rays.append(Ray("neck radius %.3g, midplane ray" % r, o, (0, 1, 0),
                        Hit(5.0 - r, neck_allow(a, r), (0.0, -1.0, 0.0))))
        d = (0.0, 0.6, 0.8)
        o = (0.0, -3.0, z - 4.0)
        rays.append(Ray("neck radius %.3g, tilted midplane ray" % r, o, d,
                        Hit(5.0 - r, neck_allow(a, r), (0.0, -0.6, -0.8))))
    return scene_of(*objects), rays


def axis_crossing(a, lo, hi):
    """x in [lo, hi] where F = f(|x - a|) + f(|x + a|) = 1 on the axis, in decimals."""
    f = quadratic(Decimal(1), Decimal(1), Decimal(2))
    ad = Decimal(repr(a))
    return float(bisect(lambda x: f(abs(x - ad)) + f(abs(x + ad)) - 1,
                        Decimal(repr(lo)), Decimal(repr(hi)), 400))


def pinch():
    """a = D_HALF: the midpoint has F = 1 and ∇F = 0. On the midplane the surface is the
    point itself, to rounding: a² is rounded by an ulp, so the disc where F >= 1 has radius
    up to sqrt(2·ulp(a²)) plus the field rounding over the curvature (same order)."""
    a = float(D_HALF)
    near = TOLERANCE + math.sqrt(8 * math.ulp(a * a)) + math.sqrt(8 * FIELD_ROUNDING)
    x_out = axis_crossing(a, a + 0.5, a + 2)
    rays = [Ray("midplane ray through the pinch point", (0, -5, 0), (0, 1, 0), Either(5, near)),
            Ray("midplane ray through the pinch point, tilted", (0, -3, -4), (0, 0.6, 0.8),
                Either(5, near)),
            Ray("along the axis from outside", (-5, 0, 0), (1, 0, 0),
                Hit(5 - x_out, TOLERANCE + ROUNDING_ULPS * ulp_at(5.0), (-1.0, 0.0, 0.0))),
            Ray("from the pinch point along the axis (inside), tmin 1e-3", (0, 0, 0),
                (1, 0, 0), Hit(x_out, TOLERANCE + ROUNDING_ULPS * ulp_at(5.0), (1.0, 0, 0)),
                tmin=1e-3)]
    return scene_of(two_points("pinch", a)), rays


def tiny():
    """A lone point with e, R scaled by σ and k by 1/σ is a sphere of radius σ. The tiny
    spheres share one object with a unit sphere 10 away, so the octrees are sized by it."""
    skeletons = [Skeleton("big", (10.0, 0.0, 0.0), UNIT_QUADRATIC)]
    rays = []
    for i, sigma in enumerate((1e-2, 1e-3, 1e-4, 1e-5, 1e-6)):
        c = (0.0, 0.0, 3.0 * i)
        skeletons.append(Skeleton("t%d" % i, c, quadratic(sigma, 1 / sigma, 2 * sigma)))
        for b in (0.0, 0.5 * sigma):
            o = (0.0, -5.0, c[2] + b)
            rays.append(Ray("radius %g, offset %g·radius" % (sigma, b / sigma), o, (0, 1, 0),
                            sphere_hit(o, (0, 1, 0), c, sigma, slope=1.0)))
    return scene_of(implicit_object("tiny", skeletons)), rays


def coincident():
    """N equal points at one place: a sphere of radius r with f(r) = 1/N."""
    objects, rays = [], []
    for i, count in enumerate((1, 2, 3, 10, 100)):
        c = (0.0, 0.0, 10.0 * i)
        objects.append(implicit_object("n%d" % count, [Skeleton("p%d" % j, c, UNIT_QUADRATIC)
                                                       for j in range(count)]))
        radius = float(quadratic_distance_for(1.0, 1.0, 2.0, Decimal(1) / count))
        slope = abs(derivative(UNIT_QUADRATIC, radius)) * count
        for b in (0.0, 0.5 * radius, 0.999 * radius):
            o = (0.0, -5.0, c[2] + b)
            rays.append(Ray("N = %d, offset %g·radius" % (count, b / radius), o, (0, 1, 0),
                            sphere_hit(o, (0, 1, 0), c, radius, slope=slope)))
    return scene_of(*objects), rays


def patch_boundary():
    """Blended pair at ±0.6 (neck radius sqrt(D_HALF² - 0.36)): rays in and near the
    bisecting plane x = 0 hit on it; F is even in x, so a ray at x = ξ hits within O(ξ²) of
    the midplane answer (ξ <= 1e-9 here: below the rounding). Ties go to the lowest index."""
    a = 0.6
    rho = neck_radius(a)
    rays = []
    for z in (0.0, 0.3, 0.7, 0.99):
        for x in (0.0, 1e-12, -1e-12, 1e-9, -1e-9):
            o = (x, -5.0, z * rho)
            depth = math.sqrt(rho * rho - (z * rho) ** 2)
            patch = "a" if x <= 0 else "b"
            rays.append(Ray("x = %g, z = %g·neck" % (x, z), o, (0, 1, 0),
                            Hit(5 - depth, neck_allow(a, depth) + 1e-12, patch=patch)))
    return scene_of(two_points("pair", a)), rays


def patch_union():
    """Unblended pair (a blends only with a far-away third point, b with nothing): the exact
    union of two unit spheres at ±0.5 with a crease on the plane x = 0. a and b are not
    neighbours, so neither rejects roots inside the other: a ray meeting the crease itself
    may report either sphere (its patch and its normal)."""
    skeletons = [Skeleton("a", (-0.5, 0.0, 0.0), UNIT_QUADRATIC),
                 Skeleton("b", (0.5, 0.0, 0.0), UNIT_QUADRATIC),
                 Skeleton("c", (0.0, 0.0, 50.0), UNIT_QUADRATIC)]
    rays = []
    for x in (0.0, 1e-9, -1e-9, 0.2, -0.2):
        for direction in ((0, 1, 0), (0.1, 1, 0.3)):
            o = add((x, 0.0, 0.0), direction, -5)
            hits = []
            for s in skeletons[:2]:
                roots = sphere_roots(o, direction, s.centre, 1.0)
                if roots:
                    hits.append((roots[0], s.name, s.centre))
            expect = None
            for t, name, c in sorted(hits):
                hit = sphere_hit(o, direction, c, 1.0, slope=1.0)
                hit.patch = name
                if expect is None:
                    expect = hit
                elif t - expect.t <= expect.allow:
                    expect.alternatives.append((hit.normal, name))
            rays.append(Ray("crosses the crease plane at x = %g, dir %s" % (x, direction), o,
                            direction, expect))
    return scene_of(implicit_object("unblended", skeletons, blends=(("a", "c"),))), rays


# Contact (libray/libobj/implicit/README.md, "Contact"): two equal quadratic points
# (UNIT_QUADRATIC, T = 1) a at (-a, 0, z) and b at (a, 0, z), a < e = 1, declared in contact.
# The deformed fields are D_A = f_A + δ(T - f_B) and D_B = f_B + δ(T - f_A) with δ(u) = u
# for u <= 0, δ >= 0 in the propagation zone 0 < u < w (w <= T) and δ(u) = 0 for u >= w.
#  - Outside B's undeformed ball (f_B < T) and without propagation, D_A = f_A: A's sphere is
#    unchanged there. With propagation it is unchanged wherever f_B = 0, i.e. at distance
#    >= R = 2 from b (u = T >= w, δ = 0).
#  - Inside B's ball D_A - T = f_A - f_B. In the lens where both balls overlap both points lie
#    within e, on the inner part f(r) = 3/2 - r²/2, so f_A - f_B = ((x - a)² - (x + a)²)/2 =
#    -2ax: zero exactly on the plane x = 0, slope 2a along x. Symmetrically D_B - T = 2ax.
# A's deformed volume therefore contains A's ball ∩ {x <= 0} (δ >= 0 outside B) and none of
# B's ball with x > 0; B's likewise: the two meet on the contact disc x = 0,
# ρ < sqrt(1 - a²), with no overlap and no gap. Without propagation they are exactly A's
# ball ∩ {x <= 0} and B's ball ∩ {x >= 0}, whose union is the union of the balls (a point of
# A's ball with x > 0 is nearer b, so in B's ball). Rays lying in the plane itself run along
# the contact surface (F = T on the whole disc): no sign change to find, so none is used.
# kb89 and the baselines ignore `contact` (a warning) and blend the pair: they fail here by
# design.
CONTACT_SUPPORT = 2.0  # R of UNIT_QUADRATIC: f = 0 beyond it


def contact_pair(name, a, z, propagations=()):
    return implicit_object(name, [Skeleton("a", (-a, 0.0, z), UNIT_QUADRATIC),
                                  Skeleton("b", (a, 0.0, z), UNIT_QUADRATIC)],
                           contacts=(("a", "b"),), propagations=propagations)


def distance(p, q):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(p, q)))


def contact_entry(o, d, centres, zone):
    """The first hit of a ray from outside both balls: the nearer of the two sphere entries
    (patch and outward normal of that sphere), checked to lie where the own field is
    undeformed: outside the other ball (no propagation; earlier points of the ray are
    outside both balls, so outside both deformed volumes), or with a zone, at distance >= R
    from the other centre while approaching it (the distance along a line is convex in t,
    so every earlier point is farther: nothing of either deformation there)."""
    roots = {name: sphere_roots(o, d, c, 1.0) for name, c in centres.items()}
    entries = sorted((r[0], name, centres[name]) for name, r in roots.items() if r)
    _, name, c = entries[0]
    other = [q for n, q in centres.items() if n != name][0]
    hit = sphere_hit(o, d, c, 1.0, slope=1.0)
    p = add(o, d, hit.t)
    if zone:
        assert distance(p, other) >= CONTACT_SUPPORT
        assert sum(di * (pi - ci) for di, pi, ci in zip(d, p, other)) < 0
    else:
        assert distance(p, other) > 1.0
    hit.patch = name
    return hit


def plane_hit(o, d, a, z):
    """The crossing of the contact plane x = 0 by a ray from inside A's ball with x < 0 (or
    B's with x > 0), through the contact disc: t = -o_x/d_x in rationals from the ray's
    numbers. It is A's exit (normal +x, patch a) and B's entry (normal -x, patch b) at once;
    either may be reported. D - T = ∓2ax there: slope 2a·|d_x|/|d| along the unit ray."""
    t = float(Fraction(-o[0]) / Fraction(d[0]))
    centre = (-a if o[0] < 0 else a, 0.0, z)
    q = add(o, d, t)
    assert distance(o, centre) < 1.0 and o[0] * d[0] < 0
    assert q[1] ** 2 + (q[2] - z) ** 2 < 1 - a * a  # inside the contact disc
    slope = 2 * a * abs(d[0]) / math.sqrt(sum(x * x for x in d))
    allow = TOLERANCE + ROUNDING_ULPS * ulp_at(*(o + (a,))) + FIELD_ROUNDING / slope
    hit = Hit(t, allow, (1.0, 0.0, 0.0), "a")
    hit.alternatives.append(((-1.0, 0.0, 0.0), "b"))
    return hit


def mirrored(v):
    return (-v[0],) + tuple(v[1:])


def contact_rays(a, z, zone):
    """Rays at the pair (±a, 0, z); zone: the pair has propagation zones (only rays whose
    answer those zones cannot change: the far sides, the plane)."""
    rho = math.sqrt(1 - a * a)  # radius of the contact disc
    centres = {"a": (-a, 0.0, z), "b": (a, 0.0, z)}
    tag = "a = %g%s" % (a, ", zones" if zone else "")
    rays = []
    # From outside along the axis direction: the far sides, unchanged.
    for h in ((0.0, 0.3, 0.5) if zone else (0.0, 0.5, 0.99)):
        for o, d in (((-5.0, h * rho, z), (1, 0, 0)), ((5.0, h * rho, z), (-1, 0, 0))):
            rays.append(Ray("%s, from outside along %s at height %g·ρ" % (tag, d, h), o, d,
                            contact_entry(o, d, centres, zone)))
    # Across the axis near the rim (no zone only: a bulge would be there).
    if not zone:
        for x in (0.2, -0.2):
            for d in ((0, 1, 0), (0.1, 1, 0.3)):
                o = add((x, 0.0, z), d, -5)
                rays.append(Ray("%s, from outside crossing x = %g, dir %s" % (tag, x, d), o, d,
                                contact_entry(o, d, centres, zone)))
    # From inside one ball across the disc: exactly the plane, whichever side.
    for q, d in (((-a, 0.0, 0.0), (1, 0, 0)), ((-0.5 * a, 0.3 * rho, -0.2 * rho), (1, 0.3, 0.2)),
                 ((-0.8 * a, 0.2 * rho, 0.1 * rho), (0.4, -0.5, 0.3))):
        for side, oq, dq in (("a", q, d), ("b", mirrored(q), mirrored(d))):
            o = add(oq, (0.0, 0.0, z))
            where = "(%.3g, %.3g, %.3g)" % oq
            rays.append(Ray("%s, inside %s from %s, dir %s" % (tag, side, where, dq), o, dq,
                            plane_hit(o, dq, a, z)))
    # From a hair before the plane inside either ball: the plane, at t = δ.
    for delta in (1e-3, 1e-6, 1e-9):
        for side, o, d in (("a", (-delta, 0.5 * rho, z), (1, 0, 0)),
                           ("b", (delta, 0.5 * rho, z), (-1, 0, 0))):
            rays.append(Ray("%s, inside %s %g before the plane, towards it" % (tag, side, delta),
                            o, d, plane_hit(o, d, a, z)))
    # Secondary rays from the plane (renderer's tmin): through the other ball to its far side
    # (D - T = ±2ax > 0 just past the plane: no root there). With zones, checked undeformed:
    # the exit lies >= R from the other centre and the ray recedes from it afterwards.
    off = 1e-5
    o = (0.0, 0.5 * rho, z)
    for name, d in (("b", (1, 0, 0)), ("a", (-1, 0, 0))):
        c = centres[name]
        hit = sphere_hit(o, d, c, 1.0, tmin=off, slope=1.0)
        hit.patch = name
        other = centres["a" if name == "b" else "b"]
        assert distance(add(o, d, hit.t), other) >= (CONTACT_SUPPORT if zone else 1.0)
        rays.append(Ray("%s, from the plane into %s, tmin 1e-5: its far side" % (tag, name),
                        o, d, hit, tmin=off))
    return rays


def contact():
    """Contact without propagation: a = 0.6 (disc radius 0.8) and a = 0.3 (deep contact:
    each point lies inside the other's ball, disc radius sqrt(0.91))."""
    objects, rays = [], []
    for i, a in enumerate((0.6, 0.3)):
        z = 10.0 * i
        objects.append(contact_pair("pair%d" % i, a, z))
        rays += contact_rays(a, z, zone=False)
    return scene_of(*objects), rays


def contact_propagation():
    """a = 0.6 with propagation zones (width 0.3; b's bulge at full height 1)."""
    a = 0.6
    scene = scene_of(contact_pair("pair", a, 0.0, (("a", 0.3), ("b", 0.3, 1))))
    return scene, contact_rays(a, 0.0, zone=True)


def negative():
    """(1) Hollow shell: +quadratic(2, 0.5, 4) and -quadratic(0.5, 2, 1.5) at one centre.
    F(0) = 1.5 - 1.5 = 0; outside r = 2 only the positive term acts: outer sphere r = 2.
    For 0.5 < r < 1.5 the negative outer part is (1 - s)², s = r - 0.5, so F = 1 reads
    1.5 - r²/8 - (1.5 - r)² = 1, i.e. 9r² - 24r + 14 = 0: inner sphere r = (4 - √2)/3.
    (2) Equal positive and negative points at one place cancel: no surface.
    (3) A negative point alone is discarded (no surface).
    (4) A carved dent: unit sphere with -quadratic(0.3, 2, 0.6) at (1.2, 0, 0); on the axis
    1.5 - x²/2 - f2(1.2 - x) = 1, solved in decimals."""
    inner = (4 - math.sqrt(2)) / 3
    shell_c = (0.0, 0.0, 0.0)
    shell = implicit_object("shell", [Skeleton("p", shell_c, quadratic(2.0, 0.5, 4.0)),
                                      Skeleton("n", shell_c, quadratic(0.5, 2.0, 1.5), -1)])
    cancel_c = (0.0, 20.0, 0.0)
    cancel = implicit_object("cancel", [Skeleton("p", cancel_c, UNIT_QUADRATIC),
                                        Skeleton("n", cancel_c, UNIT_QUADRATIC, -1)])
    alone_c = (0.0, 40.0, 0.0)
    alone = implicit_object("alone", [Skeleton("n", alone_c, UNIT_QUADRATIC, -1)])
    dent_c = (0.0, 60.0, 0.0)
    dent_kernel = quadratic(0.3, 2.0, 0.6)
    dent = implicit_object("dent", [Skeleton("p", dent_c, UNIT_QUADRATIC),
                                    Skeleton("n", add(dent_c, (1.2, 0, 0)), dent_kernel, -1)])
    f2 = quadratic(Decimal("0.3"), Decimal(2), Decimal("0.6"))
    x_dent = float(bisect(lambda x: Decimal("1.5") - x * x / 2 - f2(Decimal("1.2") - x) - 1,
                          Decimal("0.6"), Decimal(1), 400))
    plain = TOLERANCE + ROUNDING_ULPS * ulp_at(60.0)
    rays = []
    for d in ((1, 0, 0), (0.3, -0.5, 0.8)):
        dn = unit(d)
        rays.append(Ray("shell from outside, dir %s" % (d,), scale(dn, -6), dn,
                        sphere_hit(scale(dn, -6), dn, shell_c, 2.0)))
        rays.append(Ray("shell from the cavity centre, dir %s" % (d,), shell_c, dn,
                        sphere_hit(shell_c, dn, shell_c, inner, solid_outside=True)))
        o = scale(dn, 1.2)
        rays.append(Ray("shell from inside its wall, inward, dir %s" % (d,), o, scale(dn, -1),
                        sphere_hit(o, scale(dn, -1), shell_c, inner, solid_outside=True)))
    rays.append(Ray("shell, ray through the cavity off centre", (0.4, -6, 0), (0, 1, 0),
                    sphere_hit((0.4, -6, 0), (0, 1, 0), shell_c, 2.0)))
    for label, c in (("cancelling pair", cancel_c), ("negative point alone", alone_c)):
        for d in ((0, 0, 1), (0.3, 0.2, 1)):
            rays.append(Ray("%s, dir %s" % (label, d), add(c, d, -5), d, Miss()))
    rays.append(Ray("dent, along its axis", add(dent_c, (5, 0, 0)), (-1, 0, 0),
                    Hit(5 - x_dent, plain, (1.0, 0.0, 0.0))))
    return scene_of(shell, cancel, alone, dent), rays


def build():
    """Every case, in table order."""
    cases = []

    def add_case(name, category, expectation, scene, rays):
        cases.append(Case(name, category, expectation, scene, rays))

    for kernel, suffix in ((UNIT_QUADRATIC, ""), (UNIT_BLOB, "-blob")):
        what = "blob kernel, " if suffix else ""
        add_case("grazing-inside" + suffix, "grazing",
                 what + "lines 1 - δ from a unit sphere's centre, δ = 1e-3 … 1e-9: hit at the "
                 "near root", unit_sphere_scene(kernel), grazing(kernel, True))
        add_case("grazing-outside" + suffix, "grazing",
                 what + "lines 1 + δ from the centre: miss", unit_sphere_scene(kernel),
                 grazing(kernel, False))
        add_case("tangency" + suffix, "tangency",
                 what + "lines exactly 1 from the centre; eye-like, short and bounded rays: "
                 "miss, or hit at the tangent point (floor policy)",
                 unit_sphere_scene(kernel), tangency(kernel))
        add_case("far-camera" + suffix, "far camera",
                 what + "camera 1e3 … 1e7 away: error within tolerance + spacing of doubles "
                 "at D", unit_sphere_scene(kernel), far_camera(kernel))
    add_case("far-scene", "far camera", "unit spheres centred 1e3 … 1e7 from the origin, "
             "camera 5 away", *far_scene_case())
    add_case("inside-camera", "camera inside", "origins inside a unit sphere (centre and "
             "off-centre): the exit", unit_sphere_scene(UNIT_QUADRATIC), inside_camera())
    add_case("secondary", "secondary rays", "origins 1e-3 … 1e-9 inside/outside, and on the "
             "surface with tmin 1e-5: outward miss, inward the far side, exit chords",
             unit_sphere_scene(UNIT_QUADRATIC), secondary())
    add_case("thin-neck", "thin neck", "two points at ±a, neck radius 1e-1 … 1e-6 "
             "(f(d½) = ½): hit on the bisecting plane", *necks())
    add_case("pinch", "pinch point", "a = d½: zero gradient at the midpoint; tangency policy "
             "there, exact hits on the axis", *pinch())
    add_case("tiny-component", "tiny component", "spheres of radius 1e-2 … 1e-6 beside a unit "
             "sphere in one object", *tiny())
    add_case("coincident", "coincident skeletons", "N = 1 … 100 equal points: sphere of "
             "radius r with f(r) = 1/N", *coincident())
    add_case("patch-boundary", "patch boundary", "blended pair: hits on the bisecting plane "
             "and 1e-12 … 1e-9 beside it, patch a on the plane", *patch_boundary())
    add_case("patch-union", "patch boundary", "unblended pair: exact union of two spheres, "
             "crease on the bisecting plane (methods other than patches sum every skeleton, "
             "ignoring blend lists: they blend the pair and fail by design)", *patch_union())
    add_case("contact", "contact zone", "two equal balls at ±a (a = 0.6, 0.3) in contact: "
             "far sides unchanged, rays from inside stop exactly on the plane x = 0 (from a "
             "hair before it too), secondary rays from the plane reach the other far side "
             "(kb89 and the baselines ignore `contact` and blend: they fail by design)",
             *contact())
    add_case("contact-propagation", "contact zone", "a = 0.6 with propagation zones "
             "(bulges): far sides (>= R from the opponent) unchanged, the plane still exact",
             *contact_propagation())
    add_case("negative", "negative field", "hollow shell (inner sphere (4 - √2)/3 seen from "
             "the cavity), cancelling pair, negative alone, carved dent", *negative())
    return cases
