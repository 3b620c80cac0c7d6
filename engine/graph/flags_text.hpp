// flags_text.hpp: short readable names for synchronization2 stage/access masks, image layouts and planned
// barriers, used by the graph's text/Graphviz dumps and error messages ("COMPUTE|FRAGMENT", "GENERAL").
#pragma once
#include "graph/barrier_planner.hpp"

#include <string>
#include <string_view>

namespace idk::graph {

std::string stageNames(VkPipelineStageFlags2 stages);   // "NONE" for 0; unknown bits as hex
std::string accessNames(VkAccessFlags2 access);
std::string_view layoutName(VkImageLayout layout);
// "image 'color' UNDEFINED->COLOR_ATTACHMENT [NONE:NONE -> COLOR_ATTACHMENT_OUTPUT:COLOR_ATTACHMENT_WRITE]"
std::string describe(const PlannedBarrier& barrier, std::string_view resourceName);

}  // namespace idk::graph
