// ladder_report.hpp: one capability ladder as JSON, the same object in `idk info --json` ("ladders": every
// ladder) and `idk render --json` ("rungs": the ladders the render consulted, i.e. the rungs that ran), so the
// two reports can be compared field by field.
#pragma once
#include <nlohmann/json.hpp>

#include <vector>

#include "vk/features.hpp"

namespace idk::app {

inline nlohmann::json ladderJson(const vk::Ladder& l) {
    nlohmann::json rungs = nlohmann::json::array();
    for (const vk::RungOption& o : l.options)
        rungs.push_back({{"rung", vk::rungName(o.rung)}, {"mechanism", o.mechanism}, {"available", o.available},
                         {"note", o.note}});
    return {{"id", l.id},
            {"feature", l.feature},
            {"chosen", vk::rungName(l.chosen)},
            {"mechanism", l.chosenMechanism},
            {"reason", l.reason},
            {"rungs", rungs}};
}

inline nlohmann::json laddersJson(const std::vector<vk::Ladder>& ladders) {
    nlohmann::json j = nlohmann::json::array();
    for (const vk::Ladder& l : ladders) j.push_back(ladderJson(l));
    return j;
}

}  // namespace idk::app
