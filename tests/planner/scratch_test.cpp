#include <gtest/gtest.h>
#include <iostream>
#include "sims/planner/layout.h"
#include "sims/scene/builtin.h"
namespace sims::planner {
TEST(Scratch, Print) {
  std::vector<std::string> log;
  LayoutDatabase db = BuildLayoutDatabase(true, true, {}, {}, LayoutConfig{}, &log);
  for (auto& l : log) std::cout << l << "\n";
  for (auto& e : db.layouts) {
    std::cout << e.name << " kind=" << e.source.kind << " name=" << e.source.name
              << " room=" << e.source.room_id << " fp=" << e.footprint[0] << "," << e.footprint[1]
              << "," << e.footprint[2] << "," << e.footprint[3] << "\n  ";
    for (auto& n : e.nodes)
      std::cout << n.category << "(" << n.instance << (n.important ? "" : ",minor") << ") ";
    std::cout << "\n  edges:";
    for (auto& ed : e.edges)
      std::cout << " " << e.nodes[ed[0]].instance << "-" << e.nodes[ed[1]].instance;
    std::cout << "\n";
  }
  for (auto& s : scene::BuiltinRooms()) {
    std::cout << s.name << " rooms:";
    for (auto& r : s.rooms) std::cout << r.id << "/" << r.type << " ";
    std::cout << "\n";
  }
}
}  // namespace sims::planner
