#include "report.h"

#include <cstdio>

#include "fig13.h"
#include "measurements_json.h"
#include "paper_tables.h"
#include "protocol_tables.h"
#include "reference_check.h"
#include "scaling.h"
#include "text_file.h"

namespace bench {

namespace {

std::string format(const char* pattern, auto... args) {
    char text[1024];
    std::snprintf(text, sizeof text, pattern, args...);
    return text;
}

std::string machineSection(const BenchResults& r) {
    const MachineInfo& m = r.machine;
    std::string text = "## Machine\n\n";
    text += "- CPU: " + m.cpu_model + ", " + std::to_string(m.hardware_threads) + " hardware threads\n";
    text += "- CPU DDT: the serial reference, one thread\n";
    text += "- OpenImageIO " + m.oiio_version + " with " + std::to_string(m.oiio_threads) +
            " threads: the protocol's resizes and the filters (not timed in Tables 1–2)\n";
    if (r.devices.empty()) text += "- Vulkan devices: none\n";
    for (const BenchDevice& d : r.devices) text += "- Vulkan device " + d.id + ": " + d.name + "\n";
    if (!m.lp_num_threads.empty()) text += "- LP_NUM_THREADS=" + m.lp_num_threads + " (lavapipe worker threads)\n";
    text += "- Compiler " + m.compiler + ", " + m.build + " build; ddtup " + m.ddtup_version + "\n";
    text += "- Started " + m.started_utc + format(", took %.0f s\n\n", r.wall_seconds);
    return text;
}

std::string conventionsSection(const BenchResults& r) {
    std::string text = "## Protocol and timing\n\n";
    text +=
        "- Paper Sec. 6: each original is cropped (centred) to a multiple of the factor, halved log2(factor) "
        "times with OIIO's `triangle` filter in float, rounded to 8 bits once, magnified back to the original "
        "size by every method and compared with the original as 8-bit values (core/metrics.h defines the "
        "metrics; cross-correlation is the zero-mean normalised cross-correlation of the colour channels).\n";
    text +=
        "- Filters: OIIO `resize` with `triangle` (bilinear), `bspline`, `lanczos3`, `catmull-rom` at their "
        "default widths.\n";
    text += format(
        "- Timing: %u warm-up run(s), then %u timed run(s) per DDT method and image; every stage is the "
        "median of the timed runs, averaged over the set; time-sum is the sum of the stage medians.\n",
        r.warmups, r.repeats);
    text +=
        "- time-init: decode the low-resolution PNG from memory + `Backend::prepare` (build the mesh; upload on a "
        "GPU). time-comp: `Backend::optimize`. time-final: render every output row into memory (no PNG "
        "encoding; the paper's time-final saved the mesh instead). Creating a backend is not timed.\n";
    text +=
        "- Costs are Sederberg's on luma in [0, 1], so they are not on the paper's scale; improvement = mean "
        "cost-init / mean cost-final × 100 %, as the paper's figures are.\n";
    if (r.quick) text += "- **--quick**: two images cropped to 128 × 128, one factor, for CI; not for conclusions.\n";
    for (const DdtMethod& m : r.columns)
        if (!m.unavailable.empty()) text += "- " + m.label + ": n/a (" + m.unavailable + ")\n";
    return text + "\n";
}

// Fig. 13's "one image resized" points as a table, for readers without an SVG viewer.
std::string scalingTable(const BenchResults& r) {
    std::string text = "| input |";
    std::string rule = "|---|";
    std::vector<const DdtMethod*> methods;
    for (const DdtMethod& m : r.scaling_methods)
        if (m.unavailable.empty()) {
            methods.push_back(&m);
            for (const char* stage : {"init", "comp", "final", "sum"}) {
                text += " " + m.label + " " + stage + " (s) |";
                rule += "---:|";
            }
        }
    text += "\n" + rule + "\n";
    for (const ScalingResult& s : r.scaling) {
        if (s.dataset != "resized" || s.method_key != methods.front()->key) continue;
        text += format("| %u×%u |", s.width, s.height);
        for (const DdtMethod* m : methods)
            for (const ScalingResult& t : r.scaling)
                if (t.dataset == "resized" && t.method_key == m->key && t.width == s.width) {
                    const ddt::StageTimes& med = t.measurement.median;
                    text += format(" %.3f | %.3f | %.3f | %.3f |", med.init_s, med.comp_s, med.final_s,
                                   t.measurement.medianSum());
                }
        text += "\n";
    }
    return text;
}

std::string protocolSection(const BenchResults& r) {
    std::string text = "## Protocol tables: beyond Lanczos\n\n";
    text +=
        "Table 3's metrics under other ways of making the low-resolution input, the same originals and the same "
        "SSIM (core/metrics.h). Originals are cropped (centred) to a multiple of the factor's numerator (5 for "
        "×2.5), so the low-resolution size is exact. Protocols:\n\n";
    for (const Protocol& p : r.protocols) {
        text += "- **" + p.key + "** (" + p.label + "): " + describeProtocol(p) + "; factors";
        for (Magnification f : p.factors) text += " ×" + f.name();
        text += ".\n";
    }
    text +=
        "\nMethods: OIIO `triangle` (bilinear) and `lanczos3`; libvips Nohalo (vips_affine, output pixel X samples "
        "input (X + 0.5)/s − 0.5 as ddtup does); DDT plain and consistent (core/image/reconstruct.h, "
        "`Backend::reconstruct(degradationFor(sx, sy))` after `optimize`) on the CPU and on the Vulkan backend's "
        "default variant. Plain and consistent DDT share one optimisation per input.\n\n";
    text +=
        "Metrics (means of per-image values): PSNR and SSIM as core/metrics.h; GMSD (Xue et al. 2014, bench/gmsd.h: "
        "luma of the 8-bit values, 2 × 2 average and downsampling by 2, Prewitt gradients, c = 170, standard "
        "deviation of the similarity map; lower is better); overshoot (bench/overshoot.h: per output value, how far "
        "it leaves [min, max] of the 4 × 4 input pixels nearest its sample point (X + 0.5)/sx − 0.5, in 8-bit "
        "levels; the mean over all values, and the share above 4 levels; the 2 × 2 neighbourhood is in "
        "`measurements.json`).\n\n";
    for (const Upscaler& u : r.upscalers)
        if (!u.unavailable.empty()) text += "- " + u.label + ": n/a (" + u.unavailable + ")\n";
    text += "\n### Consistent DDT against Lanczos3 (the issue's criterion: ≥ 0.5 dB)\n\n" +
            toMarkdown(consistentGainTable(r)) + "\n`table3_protocols_gain.csv`\n\n";
    text += "### Quality per protocol, factor and set\n\n" + toMarkdown(protocolQualityTable(r)) +
            "\n`table3_protocols.csv`\n\n";
    text +=
        "Crops: `crops/protocols/PROTOCOL_SET_IMAGE_xFACTOR.png`, left to right Lanczos3, Nohalo, ICBI, ddtup's "
        "default (CPU), CPU DDT plain and the original.\n\n";
    return text;
}

std::string paperSections(const BenchResults& r) {
    std::string text;
    text += "## Table 1: cost and time (averages per set)\n\n" + toMarkdown(costAndTimeTable(r)) + "\n`table1.csv`\n\n";
    text += "## Table 2: time-sum (s) of every GPU variant on every Vulkan device\n\n" +
            toMarkdown(deviceTimeTable(r)) + "\n`table2.csv`\n\n";
    text += "## Table 3: reconstruction quality (means of per-image values)\n\n" + toMarkdown(qualityTable(r)) +
            "\n`table3.csv`\n\n";
    const std::string check = referenceCheckMarkdown(r);
    if (!check.empty())
        text +=
            "## Reference check against ../shared/PLATFORM.md\n\nMeans of per-image PSNR and SSIM over the bundled "
            "sets, against the reference serial DDT and OIIO filters, with the issue's tolerances.\n\n" +
            check + "\n";
    text += "## Fig. 13: runtime against input size (×" + std::to_string(kScalingFactor) + ")\n\n";
    text += "![time-sum](fig13_runtime.svg)\n\n![stages](fig13_stages.svg)\n\n";
    text += "One image (`" + r.scaling_image +
            "`) resized to n × n, plus every set image at its own size (hollow "
            "circles in the plot); all points in `fig13.csv`.\n\n" +
            scalingTable(r) + "\n";
    text +=
        "## Crops (Figs. 11 and 12)\n\n`crops/SET_IMAGE_xFACTOR.png`: left to right original, bilinear, Lanczos, "
        "CPU DDT and GPU ExpROI MaxGain (grey when not available), the 128-pixel square with the most detail, "
        "shown 2× with nearest-neighbour.\n\n";
    return text;
}

std::string reportMarkdown(const BenchResults& r) {
    std::string text = "# ddtup bench: the paper's Tables 1–3 and Fig. 13\n\n";
    text += "Červeňanský et al., *Parallel GPU-based data-dependent triangulations* (2010), Sec. 6. Sets:";
    for (const std::string& set : r.set_names) text += " " + set;
    text += ". Raw measurements: `measurements.json`.\n\n";
    text += machineSection(r);
    if (r.paper_tables) text += conventionsSection(r) + paperSections(r);
    if (!r.protocols.empty()) text += protocolSection(r);
    if (!r.notes.empty()) {
        text += "## Notes\n\n";
        for (const std::string& note : r.notes) text += "- " + note + "\n";
    }
    return text;
}

}  // namespace

void writeReport(const BenchResults& results, const std::string& out_dir) {
    if (results.paper_tables) {
        writeTextFile(out_dir + "/table1.csv", toCsv(costAndTimeTable(results)));
        writeTextFile(out_dir + "/table2.csv", toCsv(deviceTimeTable(results)));
        writeTextFile(out_dir + "/table3.csv", toCsv(qualityTable(results)));
        writeFig13(results, out_dir);
    }
    if (!results.protocols.empty()) {
        writeTextFile(out_dir + "/table3_protocols.csv", toCsv(protocolQualityTable(results)));
        writeTextFile(out_dir + "/table3_protocols_gain.csv", toCsv(consistentGainTable(results)));
    }
    writeTextFile(out_dir + "/measurements.json", measurementsJson(results));
    writeTextFile(out_dir + "/report.md", reportMarkdown(results));
}

}  // namespace bench
