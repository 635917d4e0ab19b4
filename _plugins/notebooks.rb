# frozen_string_literal: true

require "json"

# The lesson notebooks as the site publishes them: ready to run where a reader downloads
# them, outside any clone of the repository (course/notebooks.py makes the committed ones,
# which work inside a clone).
#
# - The files a notebook fetches outside a clone are published where notebooks/files.json
#   says: the example packages at their own paths (verbatim_dirs), the lesson modules of
#   course/ that notebooks import under notebooks/modules/ (copied here), and nothing else
#   of course/.
# - In each published notebook the setup cell learns the site's address (url + baseurl) and
#   a pip requirement for sw2sim from the repository's archive, when the build knows them
#   (the Pages workflow sets url, repository and repository_branch).
# - Images the Markdown shows from ../media/ are embedded as cell attachments, so that they
#   show in Jupyter, VS Code or Colab wherever the file is opened, online or not; other
#   links to the repository's files (a drawing's whole sheet) point at the site.
module Sw2simSite
  module Notebooks
    MANIFEST = "notebooks/files.json"
    PLACEHOLDER_REPOSITORY = "OWNER/REPOSITORY"
    MIME = { ".png" => "image/png", ".jpg" => "image/jpeg", ".jpeg" => "image/jpeg",
             ".gif" => "image/gif", ".svg" => "image/svg+xml" }.freeze
    # ![alt](../media/x.png) and src="../media/x.png"
    MARKDOWN_IMAGE = %r{(!\[[^\]]*\]\()\.\./(media/[^)\s]+)(\))}
    HTML_IMAGE = %r{(<img\b[^>]*\bsrc=")\.\./(media/[^"]+)(")}
    RELATIVE_LINK = %r{\]\(\.\./([^)\s]+)\)}

    module_function

    # The site's address for the setup cell: "" when the build has no url (a local build).
    def address(config)
      url = config["url"].to_s
      url.empty? ? "" : url.chomp("/") + config["baseurl"].to_s.chomp("/")
    end

    # A pip requirement for the tool and the lessons' libraries, from the repository's
    # archive of the branch the site is built from; "" while the repository is unknown.
    def tool(config)
      repository = config["repository"].to_s
      return "" if repository.empty? || repository == PLACEHOLDER_REPOSITORY

      branch = config["repository_branch"].to_s
      branch = "main" if branch.empty?
      "sw2sim[course] @ https://github.com/#{repository}/archive/refs/heads/#{branch}.zip"
    end

    # The notebook (JSON text) as published. `media` reads a file under the site by its
    # path ("media/x.png"), or gives nil.
    def publish(text, site:, tool:, media:)
      notebook = JSON.parse(text)
      notebook["cells"].each do |cell|
        if cell["cell_type"] == "code" && Array(cell.dig("metadata", "tags")).include?("setup")
          set_source(cell, fill_setup(source_of(cell), site, tool))
        elsif cell["cell_type"] == "markdown"
          embed_images(cell, media)
          absolute_links(cell, site) unless site.empty?
        end
      end
      JSON.pretty_generate(notebook, indent: " ") + "\n"
    end

    def fill_setup(source, site, tool)
      source = source.sub('site=""', "site=#{JSON.generate(site)}") unless site.empty?
      source = source.sub('tool=""', "tool=#{JSON.generate(tool)}") unless tool.empty?
      source
    end

    def embed_images(cell, media)
      text = source_of(cell)
      attachments = cell["attachments"] || {}
      embed = lambda do |before, path, after|
        data = media.call(path)
        mime = MIME[File.extname(path).downcase]
        next "#{before}../#{path}#{after}" if data.nil? || mime.nil?

        name = path.delete_prefix("media/").tr("/", "-")
        attachments[name] = { mime => [data].pack("m0") }
        "#{before}attachment:#{name}#{after}"
      end
      text = text.gsub(MARKDOWN_IMAGE) { embed.call(Regexp.last_match(1), Regexp.last_match(2), Regexp.last_match(3)) }
      text = text.gsub(HTML_IMAGE) { embed.call(Regexp.last_match(1), Regexp.last_match(2), Regexp.last_match(3)) }
      set_source(cell, text)
      cell["attachments"] = attachments unless attachments.empty?
    end

    # Links to the repository's files (../media/x-sheet.svg) point at the site instead.
    def absolute_links(cell, site)
      set_source(cell, source_of(cell).gsub(RELATIVE_LINK) { "](#{site}/#{Regexp.last_match(1)})" })
    end

    def source_of(cell)
      source = cell["source"]
      source.is_a?(Array) ? source.join : source.to_s
    end

    # nbformat's own layout: a list of lines, each but the last with its newline.
    def set_source(cell, text)
      cell["source"] = text.lines
    end
  end
end

if defined?(Jekyll)
  require "fileutils"

  Jekyll::Hooks.register :site, :post_write do |site|
    folder = File.join(site.dest, "notebooks")
    next unless File.directory?(folder)

    # The lesson modules, where notebooks/files.json says the site has them.
    manifest = site.in_source_dir(Sw2simSite::Notebooks::MANIFEST)
    if File.file?(manifest)
      JSON.parse(File.read(manifest)).values.flat_map(&:to_a).uniq.sort.each do |name, address|
        next if name == address   # the example packages: published by verbatim_dirs

        FileUtils.mkdir_p(File.dirname(File.join(site.dest, address)))
        FileUtils.cp(site.in_source_dir(name), File.join(site.dest, address))
      end
    end

    address = Sw2simSite::Notebooks.address(site.config)
    tool = Sw2simSite::Notebooks.tool(site.config)
    media = lambda do |path|
      file = File.join(site.dest, path)
      File.file?(file) ? File.binread(file) : nil
    end
    Dir.glob(File.join(folder, "*.ipynb")).sort.each do |file|
      text = Sw2simSite::Notebooks.publish(File.read(file), site: address, tool: tool, media: media)
      File.write(file, text)
    end
  end
end
