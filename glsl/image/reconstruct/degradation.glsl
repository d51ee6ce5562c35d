// The degradation D of core/image/reconstruct.cpp, one axis at a time: input pixel p of an axis
// averages the supersamples 3p + 1 + t, t in [−r, r], with the axis's taps; samples past the
// border land on the nearest one. Include after surface.glsl.

float tapX(int t) { return imageLoad(taps, t + int(push.taps_x_radius)).x; }
float tapY(int t) { return imageLoad(taps, int(2 * push.taps_x_radius + 1) + t + int(push.taps_y_radius)).x; }

// The supersample that tap t of pixel p reads on an axis of `samples` supersamples.
int tapSample(int p, int t, uint samples) { return clamp(int(kSupersamplingFactor) * p + 1 + t, 0, int(samples) - 1); }

int floorDiv3(int a) { return a >= 0 ? a / 3 : -((2 - a) / 3); }
int ceilDiv3(int a) { return a >= 0 ? (a + 2) / 3 : -(-a / 3); }

// For Dᵀ: the pixels p (of `pixels` on the axis) that read supersample s, and for each the
// taps t with tapSample(p, t) == s: t = s − 3p − 1, and at the borders every tap beyond.
struct TapRange {
    int t_lo, t_hi;
};
int firstPixelReading(int s, int radius) { return max(0, ceilDiv3(s - 1 - radius)); }
int lastPixelReading(int s, int radius, uint pixels) { return min(int(pixels) - 1, floorDiv3(s - 1 + radius)); }
TapRange tapsReading(int s, int p, int radius, uint pixels) {
    const int centre = s - int(kSupersamplingFactor) * p - 1;
    const int last_sample = int(kSupersamplingFactor * pixels) - 1;
    TapRange range;
    range.t_lo = max(-radius, s == 0 ? -radius : centre);
    range.t_hi = min(radius, s == last_sample ? radius : centre);
    return range;
}
