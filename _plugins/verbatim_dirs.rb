# frozen_string_literal: true

# Copies the directories listed under `verbatim_dirs:` in _config.yml into the site
# unchanged.
#
# Why not let Jekyll read them: Jekyll treats any file that starts with `---` as a page
# (ROS YAML files often do) and runs it through Liquid; it skips names that start with `_`
# (`__init__.py`); and the site-wide `*.py` exclusion would drop the example scripts. The
# example packages must reach the browser byte for byte, so that a page can fetch a URDF
# and its STL meshes, so these directories are excluded from the reader in _config.yml
# and added back here as plain static files.
module Sw2simSite
  class VerbatimDirs < Jekyll::Generator
    safe true
    priority :highest

    # Build and run leftovers that must not be published.
    SKIP_NAMES = %w[__pycache__ MUJOCO_LOG.TXT].freeze
    SKIP_EXTENSIONS = %w[.pyc .pyo].freeze

    def generate(site)
      Array(site.config["verbatim_dirs"]).each do |dir|
        root = site.in_source_dir(dir)
        unless File.directory?(root)
          Jekyll.logger.warn "verbatim_dirs:", "#{dir}/ does not exist; nothing copied"
          next
        end
        add_tree(site, root)
      end
    end

    private

    def add_tree(site, root)
      Dir.glob("**/*", File::FNM_DOTMATCH, base: root).sort.each do |rel|
        next if rel.split("/").any? { |part| skipped?(part) }

        full = File.join(root, rel)
        next unless File.file?(full)

        dir = File.dirname(full).delete_prefix(site.source)
        site.static_files << Jekyll::StaticFile.new(site, site.source, dir, File.basename(full))
      end
    end

    # Hidden files (.gitignore, editor state) and build leftovers stay out.
    def skipped?(part)
      part.start_with?(".") || SKIP_NAMES.include?(part) ||
        SKIP_EXTENSIONS.include?(File.extname(part))
    end
  end
end
