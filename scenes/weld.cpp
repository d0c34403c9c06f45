#include "scenes/weld.h"

#include <algorithm>
#include <tuple>

namespace sl {

std::vector<uint32_t> weld_equal_positions(const std::vector<glm::vec3>& positions) {
    std::vector<uint32_t> order(positions.size());
    for (uint32_t i = 0; i < order.size(); ++i) {
        order[i] = i;
    }
    auto less = [&](uint32_t a, uint32_t b) {
        const glm::vec3 p = positions[a], q = positions[b];
        return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
    };
    std::sort(order.begin(), order.end(), less);
    std::vector<uint32_t> id(positions.size());
    uint32_t next = 0;
    for (size_t i = 0; i < order.size(); ++i) {
        if (i > 0 && less(order[i - 1], order[i])) {
            ++next;
        }
        id[order[i]] = next;
    }
    return id;
}

}  // namespace sl
