#include "measurements_json.h"

#include "json_writer.h"
#include "scaling.h"
#include "image_file.h"

namespace bench {

namespace {

void writeMachine(JsonWriter& json, const MachineInfo& m) {
    json.key("machine").beginObject();
    json.key("cpu").value(m.cpu_model);
    json.key("hardware_threads").value(uint32_t(m.hardware_threads));
    json.key("cpu_ddt_threads").value(uint32_t(1));
    json.key("oiio_threads").value(uint32_t(m.oiio_threads));
    json.key("LP_NUM_THREADS").value(m.lp_num_threads);
    json.key("oiio_version").value(m.oiio_version);
    json.key("compiler").value(m.compiler);
    json.key("build").value(m.build);
    json.key("ddtup_version").value(m.ddtup_version);
    json.key("started_utc").value(m.started_utc);
    json.endObject();
}

void writeConventions(JsonWriter& json, const BenchResults& r) {
    json.key("conventions").beginObject();
    json.key("protocol")
        .value(
            "original cropped to a multiple of the factor; halved log2(factor) times with OIIO 'triangle' in float, "
            "rounded to 8 bits once; magnified back to the original size; compared as 8-bit values");
    json.key("time_init").value("decode the low-resolution PNG from memory + Backend::prepare");
    json.key("time_comp").value("Backend::optimize");
    json.key("time_final").value("Backend::renderRows for every output row, into memory (no PNG encoding)");
    json.key("statistic").value("median over the timed runs of each stage; time-sum = sum of the stage medians");
    json.key("warmups").value(r.warmups);
    json.key("repeats").value(r.repeats);
    json.key("scaling_repeats").value(r.scaling_repeats);
    json.key("scaling_factor").value(kScalingFactor);
    json.key("cost_units").value("Sederberg cost on luma in [0, 1], summed over edges");
    json.key("quick").value(r.quick);
    json.endObject();
}

void writeDdtMethod(JsonWriter& json, const DdtMethod& m) {
    json.beginObject();
    json.key("key").value(m.key);
    json.key("label").value(m.label);
    json.key("backend").value(m.backend);
    json.key("variant").value(m.variant);
    json.key("cost").value(std::string(ddt::costFunctionName(m.cost)));
    json.key("device").value(m.device);
    json.key("available").value(m.unavailable.empty());
    json.key("unavailable_reason").value(m.unavailable);
    json.endObject();
}

void writeMethods(JsonWriter& json, const BenchResults& r) {
    json.key("filters").beginArray();
    for (const FilterMethod& f : filterMethods())
        json.beginObject()
            .key("key")
            .value(f.key)
            .key("label")
            .value(f.label)
            .key("oiio_filter")
            .value(f.oiio_name)
            .endObject();
    json.endArray();
    json.key("ddt_columns").beginArray();
    for (const DdtMethod& m : r.columns) writeDdtMethod(json, m);
    json.endArray();
    json.key("device_methods").beginArray();
    for (const DdtMethod& m : r.device_methods) writeDdtMethod(json, m);
    json.endArray();
    json.key("scaling_methods").beginArray();
    for (const DdtMethod& m : r.scaling_methods) writeDdtMethod(json, m);
    json.endArray();
    json.key("devices").beginArray();
    for (const BenchDevice& d : r.devices)
        json.beginObject().key("id").value(d.id).key("name").value(d.name).endObject();
    json.endArray();
}

void writeTimes(JsonWriter& json, const ddt::StageTimes& t) {
    json.beginObject();
    json.key("init_s").value(t.init_s).key("comp_s").value(t.comp_s).key("final_s").value(t.final_s);
    json.key("sum_s").value(t.init_s + t.comp_s + t.final_s);
    json.endObject();
}

void writeMeasurement(JsonWriter& json, const DdtMeasurement& m) {
    json.beginObject();
    json.key("median");
    writeTimes(json, m.median);
    json.key("runs").beginArray();
    for (const DdtRun& run : m.runs) {
        const ddt::OptimizeStats& s = run.stats;
        json.beginObject();
        json.key("times");
        writeTimes(json, run.times);
        json.key("cost_init").value(s.cost_init).key("cost_final").value(s.cost_final);
        json.key("improvement_percent").value(s.improvement());
        json.key("flips").value(uint64_t(s.flips)).key("iterations").value(s.iterations);
        json.key("rounds").value(uint64_t(s.rounds)).key("dispatches").value(uint64_t(s.dispatches));
        json.key("device_ms").value(s.device_ms).key("capped").value(s.capped);
        json.endObject();
    }
    json.endArray();
    json.endObject();
}

void writeQuality(JsonWriter& json, const ddt::QualityScores& q) {
    json.beginObject();
    json.key("psnr_db").value(q.psnr).key("mse").value(q.mse).key("snr_db").value(q.snr);
    json.key("correlation").value(q.correlation).key("cross_correlation").value(q.cross_correlation);
    json.key("uiqi").value(q.uiqi).key("ssim").value(q.ssim);
    json.endObject();
}

void writeImages(JsonWriter& json, const BenchResults& r) {
    json.key("images").beginArray();
    for (const ImageResult& image : r.images) {
        json.beginObject();
        json.key("set").value(image.set).key("name").value(image.name).key("factor").value(image.factor);
        json.key("width").value(image.width).key("height").value(image.height);
        json.key("low_width").value(image.low_width).key("low_height").value(image.low_height);
        json.key("quality").beginObject();
        for (const auto& [key, q] : image.quality) {
            json.key(key);
            writeQuality(json, q);
        }
        json.endObject();
        json.key("filter_seconds").beginObject();
        for (const auto& [key, seconds] : image.filter_seconds) json.key(key).value(seconds);
        json.endObject();
        json.key("ddt").beginObject();
        for (const auto& [key, m] : image.ddt) {
            json.key(key);
            writeMeasurement(json, m);
        }
        json.endObject();
        json.endObject();
    }
    json.endArray();
}

void writeOvershoot(JsonWriter& json, const OvershootScores& o) {
    json.beginObject().key("mean_levels").value(o.mean_levels).key("share_over_4").value(o.share_over_4).endObject();
}

// The protocol tables' inputs and every per-image score, both overshoot neighbourhoods included.
void writeProtocolStudy(JsonWriter& json, const BenchResults& r) {
    json.key("protocol_study").beginObject();
    json.key("protocols").beginArray();
    for (const Protocol& p : r.protocols) {
        json.beginObject().key("key").value(p.key).key("label").value(p.label);
        json.key("definition").value(describeProtocol(p)).key("factors").beginArray();
        for (Magnification f : p.factors) json.value(f.value());
        json.endArray().endObject();
    }
    json.endArray();
    json.key("methods").beginArray();
    for (const Upscaler& u : r.upscalers)
        json.beginObject()
            .key("key")
            .value(u.key)
            .key("label")
            .value(u.label)
            .key("available")
            .value(u.unavailable.empty())
            .key("unavailable_reason")
            .value(u.unavailable)
            .endObject();
    json.endArray();
    json.key("overshoot")
        .value("per output value: max(0, v - max, min - v) over the input pixels around its sample point "
               "(X + 0.5) / sx - 0.5, in 8-bit levels; nearest_4x4: floor(p) - 1 .. floor(p) + 2, nearest_2x2: "
               "floor(p) .. floor(p) + 1, clamped");
    json.key("images").beginArray();
    for (const ProtocolImageResult& image : r.protocol_images) {
        json.beginObject();
        json.key("protocol").value(image.protocol).key("factor").value(image.factor.value());
        json.key("set").value(image.set).key("name").value(image.name);
        json.key("width").value(image.width).key("height").value(image.height);
        json.key("low_width").value(image.low_width).key("low_height").value(image.low_height);
        json.key("scores").beginObject();
        for (const auto& [key, s] : image.scores) {
            json.key(key).beginObject();
            json.key("quality");
            writeQuality(json, s.quality);
            json.key("gmsd").value(s.gmsd);
            json.key("overshoot_4x4");
            writeOvershoot(json, s.overshoot.nearest_4x4);
            json.key("overshoot_2x2");
            writeOvershoot(json, s.overshoot.nearest_2x2);
            json.endObject();
        }
        json.endObject();
        json.endObject();
    }
    json.endArray();
    json.endObject();
}

void writeScaling(JsonWriter& json, const BenchResults& r) {
    json.key("scaling_image").value(r.scaling_image);
    json.key("scaling").beginArray();
    for (const ScalingResult& s : r.scaling) {
        json.beginObject();
        json.key("dataset").value(s.dataset).key("image").value(s.image);
        json.key("width").value(s.width).key("height").value(s.height).key("method").value(s.method_key);
        json.key("measurement");
        writeMeasurement(json, s.measurement);
        json.endObject();
    }
    json.endArray();
}

}  // namespace

std::string measurementsJson(const BenchResults& r) {
    JsonWriter json;
    json.beginObject();
    json.key("tool").value("ddtup-bench");
    writeMachine(json, r.machine);
    writeConventions(json, r);
    json.key("sets").beginArray();
    for (const std::string& set : r.set_names) json.value(set);
    json.endArray();
    json.key("factors").beginArray();
    for (uint32_t factor : r.factors) json.value(factor);
    json.endArray();
    writeMethods(json, r);
    writeImages(json, r);
    writeScaling(json, r);
    writeProtocolStudy(json, r);
    json.key("notes").beginArray();
    for (const std::string& note : r.notes) json.value(note);
    json.endArray();
    json.key("wall_seconds").value(r.wall_seconds);
    json.endObject();
    return json.text() + "\n";
}

}  // namespace bench
