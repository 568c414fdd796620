#include "bake.h"
#include "vorogeo_baker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "bake_limits.h"
#include "blob_writer.h"
#include "hub_labels.h"
#include "mesh_stats.h"
#include "partition.h"
#include "patch_geodesics.h"

namespace vorogeo {

namespace {

class StageClock {
public:
    explicit StageClock(BakeReport& report) : report_(report) {}
    void end(const char* name) {
        const auto now = std::chrono::steady_clock::now();
        report_.stages.push_back({name, std::chrono::duration<double>(now - start_).count()});
        start_ = now;
    }
    void restart() { start_ = std::chrono::steady_clock::now(); }

private:
    BakeReport& report_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

uint32_t verticesUsedByFaces(const Mesh& mesh) {
    std::vector<uint8_t> used(mesh.vertexCount(), 0);
    for (const Tri& t : mesh.faces)
        for (uint32_t v : t) used[v] = 1;
    uint32_t n = 0;
    for (uint8_t u : used) n += u;
    return n;
}

void validate(const Mesh& mesh, const BakeOptions& o) {
    if (mesh.faceCount() == 0) throw std::invalid_argument("the mesh has no faces");
    const uint32_t used = verticesUsedByFaces(mesh);
    if (o.n1 > used)
        throw std::invalid_argument("--n1 " + std::to_string(o.n1) + " is larger than the " + std::to_string(used) +
                                    " vertices used by faces");
    if (o.n2 > used)
        throw std::invalid_argument("--n2 " + std::to_string(o.n2) + " is larger than the " + std::to_string(used) +
                                    " vertices used by faces");
    if (!(o.delta < 0 || (std::isfinite(o.delta) && o.delta < 1)))
        throw std::invalid_argument("--delta must be a finite fraction of the bounding-box diagonal in [0, 1)");
    if (o.marginRings > 8) throw std::invalid_argument("--margin-rings must be in [0, 8]");
    if (o.compressionLevel < 0 || o.compressionLevel > 22)
        throw std::invalid_argument("compression level must be in [1, 22] (0: automatic)");
    if (o.compact && !o.compress)
        throw std::invalid_argument("--compact codes the distances for compression: it cannot go with --no-compress");
    if (o.innerRowsAtOpen && !(o.compact && o.hubLabels))
        throw std::invalid_argument("--inner-rows-at-open leaves out a part of the hub labels of a compact blob: it needs --compact and --hub-labels");
}

}  // namespace

int automaticLevel(bool coded, uint64_t payloadBytes) {
    if (!coded) return 9;
    if (payloadBytes <= (uint64_t(32) << 20)) return 19;
    return payloadBytes <= (uint64_t(1) << 30) ? 17 : 11;
}

std::vector<uint8_t> bakeMesh(const Mesh& mesh, const BakeOptions& options, BakeReport& report,
                              const BakeProgress& reportProgress) {
    validate(mesh, options);
    const uint64_t vertices = verticesUsedByFaces(mesh);
    checkBakeLimits(vertices, options);
    const BakeProgress progress = [&](const char* stage, double fraction) {
        checkMemoryDuringBake(options, stage);
        if (reportProgress) reportProgress(stage, fraction);
    };
    report = BakeReport();
    report.vertices = mesh.vertexCount();
    report.faces = mesh.faceCount();
    report.compressed = options.compress;
    report.compact = options.compact;
    report.innerRowsAtOpen = options.innerRowsAtOpen;
    StageClock clock(report);

    PartitionOptions po;
    po.firstLayerSeeds = options.n1;
    po.secondLayerSeeds = options.n2;
    po.seed = options.seed;
    const Partition partition = partitionMesh(mesh, po, progress);
    report.firstPatches = partition.first.size();
    report.secondPatches = partition.second.size();
    for (const Patch& p : partition.first) {
        report.firstBorder += p.border.size();
        report.firstInterior += p.interior.size();
    }
    for (const Patch& p : partition.second) {
        report.secondBorder += p.border.size();
        report.secondInterior += p.interior.size();
    }
    clock.end("partition");

    PatchGeodesicsOptions go;
    go.marginRings = options.marginRings;
    go.firstLayer = options.exactFirstLayer ? PatchGeodesicsOptions::FirstLayer::Exact
                                            : PatchGeodesicsOptions::FirstLayer::Composed;
    PatchGeodesics geodesics = computePatchGeodesics(mesh, partition, go, progress);
    report.sourceRuns = geodesics.stats.sourceRuns;
    report.stages.push_back({"second-layer geodesics", geodesics.stats.secondLayerSeconds});
    report.stages.push_back({options.exactFirstLayer ? "first-layer geodesics" : "first-layer overlay",
                             geodesics.stats.firstLayerSeconds});
    clock.restart();  // the two entries above time this stage

    const double diagonal = computeStats(mesh).bboxDiag;
    report.bboxDiagonal = diagonal;
    report.delta = options.delta < 0 ? kDefaultDelta : options.delta;
    report.deltaAbsolute = report.delta * diagonal;
    // delta_sl = delta / gamma, gamma = second-layer patches per first-layer patch (thesis eq. 3.1).
    const double gamma = double(partition.second.size()) / double(std::max<size_t>(1, partition.first.size()));
    report.deltaSecond = report.deltaAbsolute / gamma;
    if (progress) progress("pruning", 0.0);
    std::vector<uint8_t> firstInactive, secondInactive;
    report.firstPrune = pruneLayer(mesh, geodesics.first, report.deltaAbsolute, true, firstInactive);
    report.secondPrune = pruneLayer(mesh, geodesics.second, report.deltaSecond, false, secondInactive);
    if (progress) progress("pruning", 1.0);
    clock.end("pruning");

    BlobParams params;
    params.seed = options.seed;
    params.n1 = options.n1;
    params.n2 = options.n2;
    params.marginRings = options.marginRings;
    params.delta = report.delta;
    params.bboxDiagonal = diagonal;
    if (progress) progress("writing blob", 0.0);
    std::vector<uint8_t> buffer = buildGraphBuffer(mesh, partition, geodesics.first, geodesics.second,
                                                   secondInactive, params, Landmarks(), report.quantisationMaxAbs);
    clock.end("serialise");
    if (progress) progress("landmarks", 0.0);
    const Landmarks landmarks = computeLandmarks(buffer, options.landmarks);
    buffer = buildGraphBuffer(mesh, partition, geodesics.first, geodesics.second, secondInactive, params, landmarks,
                              report.quantisationMaxAbs);
    if (progress) progress("landmarks", 1.0);
    clock.end("landmarks");
    Payload payload;
    if (options.innerRowsAtOpen) {
        // A reader must fit each patch's search in its fixed memory: checked before the labels.
        const std::string tooLarge = innerRowsAtOpenExcess(buffer);
        if (!tooLarge.empty()) throw std::runtime_error("--inner-rows-at-open: " + tooLarge);
    }
    if (options.hubLabels) {
        if (progress) progress("hub labels", 0.0);
        HubLabels hubs = computeHubLabels(
            buffer, [&](double f) { if (progress) progress("hub labels", f); },
            [&](const HubLabelSizes& sizes) {
                checkHubLabelLimits(buffer.size(), sizes, vertices, options, residentBytes());
            });
        report.hubs = hubs.hubCount;
        report.hubTreeNodes = hubs.tree.size();
        report.hubLabelEntries = hubs.columns.size();
        report.hubInnerEntries = hubs.inner.size();
        buffer = buildGraphBuffer(mesh, partition, geodesics.first, geodesics.second, secondInactive, params,
                                  landmarks, report.quantisationMaxAbs, hubs);
        // Zeros stand for rows left to the readers (the exit lists were made from them).
        if (options.innerRowsAtOpen) std::fill(hubs.inner.begin(), hubs.inner.end(), uint16_t(0));
        payload = withLabelTables(std::move(buffer), hubs);
        hubs = HubLabels();  // its tables are in the payload now
        clock.end("hub labels");
    } else {
        payload.flatbufferSize = buffer.size();
        payload.bytes = std::move(buffer);
    }
    report.flatbufferBytes = payload.flatbufferSize;
    const int level = options.compressionLevel > 0 ? options.compressionLevel
                                                   : automaticLevel(options.compact, payload.bytes.size());
    std::vector<uint8_t> blob =
        packContainer(std::move(payload), options.compress, options.compact, level, options.innerRowsAtOpen);
    report.blobBytes = blob.size();
    if (progress) progress("writing blob", 1.0);
    clock.end(options.compress ? "compress" : "container");
    return blob;
}

}  // namespace vorogeo

namespace vorogeo {

BakeResult bake(const Mesh& mesh, const BakeOptions& options, const BakeProgress& progress,
                const std::atomic<bool>* cancel) {
    // Cancellation rides on the progress calls, which every stage makes regularly; the
    // exception leaves TBB's parallel loops the way any exception does.
    const BakeProgress checked = [&](const char* stage, double fraction) {
        if (cancel && cancel->load(std::memory_order_relaxed)) throw BakeCancelled();
        if (progress) progress(stage, fraction);
    };
    if (cancel && cancel->load()) throw BakeCancelled();
    BakeResult r;
    r.blob = bakeMesh(mesh, options, r.report, checked);
    if (cancel && cancel->load()) throw BakeCancelled();
    return r;
}

}  // namespace vorogeo
