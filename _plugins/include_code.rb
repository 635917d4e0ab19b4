# frozen_string_literal: true

# {% include_code path/from/the/repository/root.py %}
#
# Inserts the text of a repository file, so a page shows the file that the tests run
# rather than a copy that drifts. Use it alone on a line inside a fenced block:
#
#     ```python
#     {% include_code examples/example_1/scripts/periodic_force.py %}
#     ```
#     {: data-file="examples/example_1/scripts/periodic_force.py"}
#
# The optional attribute line names the file above the block (see _plugins/code_blocks.rb).
#
# Inside an indented fence (in a list item), say how far the fence is indented, so that
# every inserted line stays inside the block:
#
#     {% include_code examples/example_1/scripts/periodic_force.py indent=3 %}
#
# A tag's output is never parsed again by Liquid, so `{{ ... }}` in the file is shown as
# is. (A file holding a line of three backticks would close the fence early: fence such a
# file with four.) The path is relative to the site source (the repository root); absolute paths and
# `..` are refused so a page cannot reach outside the repository.
module Sw2simSite
  class IncludeCodeTag < Liquid::Tag
    SYNTAX = /\A\s*(?<path>"[^"]+"|'[^']+'|\S+)(?:\s+indent=(?<indent>\d+))?\s*\z/.freeze

    def initialize(tag_name, markup, parse_context)
      super
      match = SYNTAX.match(markup)
      unless match
        raise Liquid::SyntaxError,
              "include_code: expected `{% include_code path/to/file [indent=N] %}`, " \
              "got `{% include_code#{markup}%}`"
      end
      @path = match[:path].delete_prefix('"').delete_suffix('"')
                          .delete_prefix("'").delete_suffix("'")
      @indent = match[:indent].to_i
    end

    def render(context)
      site = context.registers[:site]
      page = context.registers[:page]
      where = page && page["path"] ? page["path"] : "(unknown page)"

      if @path.start_with?("/", "~") || @path.split(%r{[/\\]}).include?("..")
        raise Liquid::ArgumentError,
              "include_code in #{where}: '#{@path}' must be a path relative to the " \
              "repository root, without '..'"
      end

      file = File.join(site.source, @path)
      unless File.file?(file)
        raise Liquid::ArgumentError,
              "include_code in #{where}: file '#{@path}' not found (looked in #{site.source})"
      end

      text = File.read(file, encoding: "UTF-8")
      unless text.valid_encoding?
        raise Liquid::ArgumentError, "include_code in #{where}: '#{@path}' is not UTF-8 text"
      end

      # The closing fence follows the tag on its own line: drop the file's final newline
      # (and trailing blank lines), or the block would end with an empty line.
      lines = text.gsub("\r\n", "\n").sub(/\s+\z/, "").split("\n", -1)
      pad = " " * @indent
      # The tag's own line is already indented; the rest need the fence's indentation.
      lines.each_with_index.map { |line, i| i.zero? || line.empty? ? line : pad + line }.join("\n")
    end
  end
end

Liquid::Template.register_tag("include_code", Sw2simSite::IncludeCodeTag)
