#include "quality_report.h"
#include "core/text_table.h"

#include <algorithm>
#include <cstdio>

namespace cavity::flags {

namespace {

// "+0.0123" or "-0.0123".
std::string signedNumber(double v) {
    std::string text = TextTable::number(v, 4);
    if (v >= 0) text.insert(text.begin(), '+');
    return text;
}

}  // namespace

bool cannotTellApart(const QualityRow& better, const QualityRow& worse) {
    const auto [low, high] = measure::maeDifference(better, worse);
    return low <= 0 && high >= 0;
}

void printQuality(const QualityOptions& o, std::vector<QualityRow> rows,
                  const std::map<std::pair<std::string, int>, double>& costs) {
    if (o.sharedReach)
        std::printf("reach: shared, every kernel and the truth at R = %g\n", o.radius);
    else
        std::printf("reach: seed, each kernel at its own default reach, the truth at R = 0.5\n");
    if (!o.switches.empty()) {
        std::string set;
        for (const auto& [name, value] : o.switches)
            if (const auto* decl = kernels::findParam(name)) set += " --" + name + " " + kernels::valueText(*decl, value);
        std::printf("set for every kernel that declares it:%s\n", set.c_str());
    }
    using A = TextTable::Align;
    // Each scene's rows, most accurate first.
    std::stable_sort(rows.begin(), rows.end(), [](const QualityRow& a, const QualityRow& b) {
        return a.scene != b.scene ? a.scene < b.scene : a.meanAbsError < b.meanAbsError;
    });
    TextTable table({{"scene", A::Left}, {"kernel", A::Left}, {"samples", A::Right}, {"MAE", A::Right},
                     {"95% interval", A::Right}, {"", A::Left}, {"max", A::Right}, {"mean AO", A::Right},
                     {"truth", A::Right}, {"cost ms", A::Right}, {"vs committed", A::Right}});
    int ties = 0, edited = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
        const auto& r = rows[i];
        const auto c = costs.find({r.kernel, r.samples});
        const bool tie = i > 0 && rows[i - 1].scene == r.scene && cannotTellApart(rows[i - 1], r);
        ties += tie;
        if (r.committedMae) ++edited;
        table.add({r.scene, r.kernel + (r.committedMae ? "*" : ""), std::to_string(r.samples), TextTable::number(r.meanAbsError, 4),
                   TextTable::number(r.maeLow, 4) + "-" + TextTable::number(r.maeHigh, 4), tie ? "~" : "",
                   TextTable::number(r.maxAbsError, 4), TextTable::number(r.meanAo, 4), TextTable::number(r.meanTruth, 4),
                   c == costs.end() ? "-" : TextTable::number(c->second, 4),
                   r.committedMae ? signedNumber(r.meanAbsError - *r.committedMae) : std::string()});
    }
    table.print();
    if (edited)
        std::printf("*: measured with the --kernel-source edit, which changed its AO; vs committed: its MAE minus the "
                    "committed kernel's\n");
    if (ties)
        std::printf("~: the 95%% interval of its MAE's difference from the row above's (a paired bootstrap over %d px "
                    "tiles) holds 0: the two cannot be told apart at this size\n", measure::kTileSide);
}

}  // namespace cavity::flags
