#include "ui/pass_panel.h"

namespace gi::ui {

std::unique_ptr<PassPanel> makeVCTPanel(const EditorOptions& options);
std::unique_ptr<PassPanel> makeVolumetricPanel(const EditorOptions& options);
std::unique_ptr<PassPanel> makeEnvironmentPanel(const EditorOptions& options);

const std::vector<PassPanelEntry>& passPanels() {
    static const std::vector<PassPanelEntry> panels{
        {VCTSettings::kSection, &makeVCTPanel},
        {VolumetricSettings::kSection, &makeVolumetricPanel},
        {EnvironmentSettings::kSection, &makeEnvironmentPanel},
    };
    return panels;
}

}  // namespace gi::ui
